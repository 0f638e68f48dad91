// bullet_drape: the drape (support/drape_figures.hpp) in Bullet's soft body, for the comparison
// of docs/performance.md ("Against Bullet"). Bullet's cloth as an engine developer would make it:
// btSoftBodyHelpers::CreatePatch, 81 x 81 points, gendiags (structural links and one diagonal
// per cell), no bending links, total mass 1.9 kg, in a btSoftRigidDynamicsWorld over a static
// btSphereShape (r 0.5 m) and a static ground box (top at y = -1). The best-tuned setting: 50
// position iterations (m_cfg.piterations), collision margin 0.025 m, dt = 1/60 s, one substep per
// frame. Friction: the soft body's kDF = 1 times the rigid bodies' 0.5, i.e. 0.5
// as in massspring_drape; self-collision off (Bullet's default). Debian's libbullet-dev, single
// precision, one thread.
//
// It drops the cloth, runs the frames and prints the figures of support/drape_figures.hpp; the
// time (CPU) is stepSimulation plus the sparse SDF's GarbageCollect (as Bullet's demos call it) per
// frame, nothing of the figures.
//
//   bullet_drape [--seconds S (default 3)] [--crossings]
#include <BulletSoftBody/btSoftBody.h>
#include <BulletSoftBody/btSoftBodyHelpers.h>
#include <BulletSoftBody/btSoftBodyRigidBodyCollisionConfiguration.h>
#include <BulletSoftBody/btSoftRigidDynamicsWorld.h>
#include <btBulletDynamicsCommon.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "support/drape_figures.hpp"

namespace {

massspring::Points<double> positions(const btSoftBody& body) {
  massspring::Points<double> x(body.m_nodes.size(), 3);
  for (int i = 0; i < body.m_nodes.size(); ++i) {
    const btVector3& p = body.m_nodes[i].m_x;
    x.row(i) << double(p.x()), double(p.y()), double(p.z());
  }
  return x;
}

int node_index(const btSoftBody& body, const btSoftBody::Node* n) {
  return int(n - &body.m_nodes[0]);
}

}  // namespace

int main(int argc, char** argv) {
  double seconds = 3;
  drape::Watch watch;
  if (!drape::parse(argc, argv, seconds, watch.count_crossings,
                    [](const std::string&, const char*, int&) { return false; })) {
    std::fprintf(stderr, "usage: bullet_drape [--seconds S > 0] [--crossings]\n");
    return 2;
  }
  const btScalar dt = btScalar(1.0 / 60);
  const int frames = std::max(1, int(std::lround(seconds / double(dt))));

  btSoftBodyRigidBodyCollisionConfiguration configuration;
  btCollisionDispatcher dispatcher(&configuration);
  btDbvtBroadphase broadphase;
  btSequentialImpulseConstraintSolver solver;
  btSoftRigidDynamicsWorld world(&dispatcher, &broadphase, &solver, &configuration);
  const btVector3 gravity(0, btScalar(-drape::kGravity), 0);
  world.setGravity(gravity);
  btSoftBodyWorldInfo& info = world.getWorldInfo();
  info.m_gravity = gravity;
  info.m_sparsesdf.Initialize();

  // The static sphere and ground box.
  btSphereShape sphere_shape(btScalar(drape::kRadius));
  btRigidBody sphere(btRigidBody::btRigidBodyConstructionInfo(0, nullptr, &sphere_shape));
  sphere.setFriction(btScalar(drape::kFriction));
  world.addRigidBody(&sphere);
  btBoxShape ground_shape(btVector3(5, btScalar(0.5), 5));
  btRigidBody::btRigidBodyConstructionInfo ground_info(0, nullptr, &ground_shape);
  ground_info.m_startWorldTransform.setIdentity();
  ground_info.m_startWorldTransform.setOrigin(btVector3(0, btScalar(drape::kFloor - 0.5), 0));
  btRigidBody ground(ground_info);
  ground.setFriction(btScalar(drape::kFriction));
  world.addRigidBody(&ground);

  // The cloth: corner00 -> corner10 along x, corner00 -> corner01 along z.
  const btScalar h = btScalar(drape::kHeight), w = btScalar(drape::kWidth / 2);
  btSoftBody* cloth = btSoftBodyHelpers::CreatePatch(
      info, btVector3(-w, h, -w), btVector3(w, h, -w), btVector3(-w, h, w), btVector3(w, h, w),
      drape::kSide, drape::kSide, 0, true);
  cloth->m_cfg.piterations = 50;
  cloth->m_cfg.kDF = 1;
  cloth->getCollisionShape()->setMargin(btScalar(0.025));
  cloth->setTotalMass(btScalar(drape::kMass));
  world.addSoftBody(cloth);

  // Its surface and links, as indices, for the figures.
  massspring::Triangles surface(cloth->m_faces.size(), 3);
  for (int f = 0; f < cloth->m_faces.size(); ++f)
    for (int k = 0; k < 3; ++k) surface(f, k) = node_index(*cloth, cloth->m_faces[f].m_n[k]);
  massspring::Edges links(cloth->m_links.size(), 2);
  Eigen::VectorXd rest_lengths(cloth->m_links.size());
  for (int e = 0; e < cloth->m_links.size(); ++e) {
    links(e, 0) = node_index(*cloth, cloth->m_links[e].m_n[0]);
    links(e, 1) = node_index(*cloth, cloth->m_links[e].m_n[1]);
    rest_lengths(e) = double(cloth->m_links[e].m_rl);
  }

  drape::FrameTimer timer;
  massspring::Points<double> x;
  for (int k = 0; k < frames; ++k) {
    timer.start();
    world.stepSimulation(dt, 1, dt);
    info.m_sparsesdf.GarbageCollect();
    timer.stop();
    x = positions(*cloth);
    watch.frame_end(x, surface);
  }
  const bool ok = x.allFinite();
  char engine[160];
  std::snprintf(engine, sizeof engine,
                "Bullet %d.%02d soft body (%s), %d nodes, %d links, %d faces, 50 position "
                "iterations, margin 0.025 m",
                btGetVersion() / 100, btGetVersion() % 100,
                sizeof(btScalar) == 4 ? "float" : "double", cloth->m_nodes.size(),
                cloth->m_links.size(), cloth->m_faces.size());
  drape::print(engine, double(dt), frames, timer, drape::figures(x, links, rest_lengths), watch,
               ok);

  world.removeSoftBody(cloth);
  delete cloth;
  world.removeRigidBody(&ground);
  world.removeRigidBody(&sphere);
  return ok ? 0 : 1;
}
