// finflex: deform fish meshes with the secant-surface bend on any OpenCL device.
//
//   finflex deform --in PATH --out PATH --m VALUE [--mode paper|exact]
//                  [--normals rotate|jacobian] [--frame auto|identity] [--clamp] [--device NAME]
//   finflex check --in PATH [--device NAME]
//   finflex rig-info --in PATH --rig RIG.json [--labels FILE]
//   finflex bench --mesh PATH --instances N --frames F [--mode paper|exact]
//                 [--rig RIG.json [--path fused|passes]] [--device NAME] [--json]
//   finflex subdivide --in PATH --levels N --out PATH
//   finflex swim [--fish N] [--seconds S] ... [--out DIR [--annotate]]
//   finflex bake --out DIR [--species MESH:RIG] [--frames N] ...
//   finflex info
#include "tool.hpp"

int main(int argc, char** argv) { return finflex::cli::run_tool(argc, argv); }
