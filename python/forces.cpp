// The force terms (forces/*.hpp, and contact/fosssim/penalty.hpp's PenaltyForce) as Python values, and
// MassSpringSystem.add_force for each. Every constructor validates as the C++ one does; add_force
// copies the term into the system (changing the Python object afterwards changes nothing).

#include <massspring/contact/fosssim/penalty.hpp>
#include <massspring/forces/vortex.hpp>
#include <vector>

#include "bindings.hpp"

namespace massspring::python {

namespace {

using GravitationalAttraction = massspring::GravitationalAttraction<double>;
using VortexForce = massspring::VortexForce<double>;
using PenaltyForce = contact::PenaltyForce<double>;

// Per-pair values: one number for every pair, or one per pair.
Vec per_pair(const py::handle& x, const char* what, Eigen::Index pairs) {
  return real_vector(x, what, pairs, true);
}

std::vector<GravitationalAttraction::Pair> attraction_pairs(const py::handle& pairs,
                                                            const py::handle& G) {
  const IndexMatrix p = index_matrix(pairs, "gravitational attraction: pairs", 2);
  const Vec g = per_pair(G, "gravitational attraction: G", p.rows());
  std::vector<GravitationalAttraction::Pair> out;
  for (Eigen::Index k = 0; k < p.rows(); ++k) out.push_back({p(k, 0), p(k, 1), g(k)});
  return out;
}

template <class Term>
void add_force_overload(py::class_<System>& system) {
  system.def(
      "add_force",
      [](System& s, const Term& term) {
        check_idle(&s, "add_force");
        return s.add_force(term);
      },
      py::arg("term"), "Adds a copy of the force term; returns its index in forces. New revision.");
}

}  // namespace

void bind_forces(py::module_& m) {
  py::class_<Gravity<double>>(m, "Gravity",
                              "F_i = m_i g: a uniform acceleration g [m/s^2] on every point.")
      .def(py::init([](const py::handle& g) { return Gravity<double>(vector3(g, "gravity")); }),
           py::arg("g"))
      .def_property_readonly("g", [](const Gravity<double>& t) { return copy_array(t.g, true); });

  py::class_<ConstantForce<double>>(m, "ConstantForce",
                                    "F_i = f: the same force [N] on every point.")
      .def(py::init([](const py::handle& f) {
             return ConstantForce<double>(vector3(f, "constant force"));
           }),
           py::arg("force"))
      .def_property_readonly(
          "force", [](const ConstantForce<double>& t) { return copy_array(t.force, true); });

  py::class_<LinearDrag<double>>(m, "LinearDrag", "F_i = -beta v_i, beta [N s/m] (not per mass).")
      .def(py::init<double>(), py::arg("beta"))
      .def_readonly("beta", &LinearDrag<double>::beta);

  py::class_<GravitationalAttraction>(
      m, "GravitationalAttraction",
      "F_i = G m_i m_j / (l^2 + eps^2)^(3/2) d towards j, for each listed pair (i, j).\n"
      "GravitationalAttraction(pairs, G, softening=0): pairs (k, 2) integer, G one number or (k,)")
      .def(py::init([](const py::handle& pairs, const py::handle& G, double softening) {
             return GravitationalAttraction(attraction_pairs(pairs, G), softening);
           }),
           py::arg("pairs"), py::arg("G"), py::arg("softening") = 0.0)
      .def_static("all_pairs", &GravitationalAttraction::all_pairs, py::arg("n"), py::arg("G"),
                  py::arg("softening") = 0.0, "Every pair of the first n points, one G.")
      .def_property_readonly("pairs", [](const GravitationalAttraction& t) {
        std::vector<std::pair<int, int>> out;
        for (const auto& p : t.pairs()) out.emplace_back(p.i, p.j);
        return out;
      });

  py::class_<VortexForce>(m, "VortexForce",
                          "FOSSSim's vortex force between listed pairs (forces/vortex.hpp).\n"
                          "VortexForce(pairs, kbs, kvc): pairs (k, 2) integer, kbs and kvc one "
                          "number or (k,) each")
      .def(py::init([](const py::handle& pairs, const py::handle& kbs, const py::handle& kvc) {
             const IndexMatrix p = index_matrix(pairs, "vortex force: pairs", 2);
             const Vec b = per_pair(kbs, "vortex force: kbs", p.rows());
             const Vec v = per_pair(kvc, "vortex force: kvc", p.rows());
             std::vector<VortexForce::Pair> list;
             for (Eigen::Index k = 0; k < p.rows(); ++k)
               list.push_back({p(k, 0), p(k, 1), b(k), v(k)});
             return VortexForce(std::move(list));
           }),
           py::arg("pairs"), py::arg("kbs"), py::arg("kvc"))
      .def_property_readonly("pairs", [](const VortexForce& t) {
        std::vector<std::pair<int, int>> out;
        for (const auto& p : t.pairs()) out.emplace_back(p.i, p.j);
        return out;
      });

  py::enum_<contact::BroadPhaseKind>(m, "BroadPhaseKind")
      .value("AllPairs", contact::BroadPhaseKind::AllPairs)
      .value("Grid", contact::BroadPhaseKind::Grid);

  py::class_<PenaltyForce>(
      m, "PenaltyForce",
      "Penalty contact (contact/fosssim/penalty.hpp): E = k/2 (s - |n|)^2 for particles, edges and "
      "planes closer than s = radii + thickness.\n"
      "PenaltyForce(radii, k, thickness, edges=None, edge_radii=None, planes=(), "
      "broad_phase=BroadPhaseKind.AllPairs): radii (n,) [m]; edges (e, 2) integer with "
      "edge_radii (e,) [m]; planes a list of (point, normal) pairs; k [N/m]")
      .def(py::init([](const py::handle& radii, double k, double thickness, const py::handle& edges,
                       const py::handle& edge_radii, const py::handle& planes,
                       contact::BroadPhaseKind broad_phase) {
             contact::ContactGeometry<double> g;
             g.radii = real_vector(radii, "penalty force: radii", -1);
             if (!edges.is_none()) g.edges = index_matrix(edges, "penalty force: edges", 2);
             g.edge_radii = edge_radii.is_none()
                                ? Vec(Vec::Zero(g.edges.rows()))
                                : real_vector(edge_radii, "penalty force: edge_radii", -1);
             if (!py::isinstance<py::sequence>(planes))
               throw Error("penalty force: planes: expected a list of (point, normal) pairs");
             for (const py::handle plane : py::reinterpret_borrow<py::sequence>(planes)) {
               if (!py::isinstance<py::sequence>(plane) || py::len(plane) != 2)
                 throw Error("penalty force: planes: expected a list of (point, normal) pairs");
               const auto pn = py::reinterpret_borrow<py::sequence>(plane);
               g.planes.push_back({vector3(pn[0], "penalty force: plane point"),
                                   vector3(pn[1], "penalty force: plane normal")});
             }
             return PenaltyForce(std::move(g), k, thickness, broad_phase);
           }),
           py::arg("radii"), py::arg("k"), py::arg("thickness"), py::arg("edges") = py::none(),
           py::arg("edge_radii") = py::none(), py::arg("planes") = py::tuple(),
           py::arg("broad_phase") = contact::BroadPhaseKind::AllPairs)
      .def_property_readonly("stiffness", &PenaltyForce::stiffness)
      .def_property_readonly("thickness", &PenaltyForce::thickness);

  py::class_<System> system = system_class(m);
  add_force_overload<Gravity<double>>(system);
  add_force_overload<ConstantForce<double>>(system);
  add_force_overload<LinearDrag<double>>(system);
  add_force_overload<GravitationalAttraction>(system);
  add_force_overload<VortexForce>(system);
  add_force_overload<PenaltyForce>(system);
}

}  // namespace massspring::python
