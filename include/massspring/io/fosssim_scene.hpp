#pragma once
/// @file
/// @brief read_fosssim_scene(), write_fosssim_scene() and make_fosssim_system(): the 2D XML scenes
/// of FOSSSim (Columbia's "Animation and CGI Motion" course), read strictly with pugixml. The
/// public include; the parts are in io/fosssim/.
///
/// The schema (docs/scenes.md): a root `<scene>` holding
/// - `<duration time="T"/>` and `<integrator type="..." dt="h"/>`, both required, once each;
///   types explicit-euler, symplectic-euler (Theme 2: forward-backward-euler),
///   linearized-implicit-euler, implicit-euler;
/// - `<particle m px py vx vy fixed [radius] [tag]/>`: index = order of appearance; z = 0;
///   radius (default 0.1) is the collision radius;
/// - `<edge i j [radius]/>`: index = order of appearance; collision geometry (a capsule, radius
///   default 0.015) with or without a spring;
/// - `<springforce edge k l0 [b]/>`: a spring on the endpoints of edge #edge (b defaults to 0);
/// - `<simplegravity fx fy/>` (an acceleration), `<gravitationalforce i j G/>`,
///   `<dragdamping b/>`, `<vortexforce i j kbs kvc/>`;
/// - Theme 2: `<halfplane px py nx ny/>`, `<collision type [COR] [k] [thickness] [maxiters]/>`
///   (at most one), `<collisiondetection type="allpairs|contest"/>` (at most one);
/// - `<description text/>`, `<scenetag tag/>`: kept; `<particlecolor>`, `<edgecolor>`,
///   `<halfplanecolor>`, `<particlepath>`, `<backgroundcolor>`, `<viewport>`, `<maxsimfreq>`:
///   rendering only, ignored.
/// Anything else is refused. Attributes written without a blank between them (`vx="0"vy="0"`,
/// not XML but read by FOSSSim's parser) are read as FOSSSim reads them.

#include "massspring/io/fosssim/parse.hpp"
#include "massspring/io/fosssim/reader.hpp"
#include "massspring/io/fosssim/scene.hpp"
#include "massspring/io/fosssim/system.hpp"
#include "massspring/io/fosssim/theme2.hpp"
#include "massspring/io/fosssim/write.hpp"
