// bspbench order: build a tree, write its fragments as PREFIX.obj (face k is fragment k) and the
// back-to-front order from one eye as PREFIX.order.json, so another tool can draw or check it.
#include <cmath>
#include <cstdio>
#include <iostream>
#include <nlohmann/json.hpp>

#include "cli/commands.h"
#include "cli/run_args.h"
#include "common/errors.h"
#include "io/atomic_file.h"
#include "metrics/kernel_stats.h"
#include "tree/exact_traverse.h"
#include "tree/traverse.h"

namespace bsp::cli {

namespace {

// One face per fragment in fragment order; coordinates printed round-trip exact (%.17g).
std::string fragments_obj(const Tree& tree) {
  std::string out = "# bspbench order: face k (0-based, in file order) is fragment k\n";
  char line[128];
  for (const FragmentView f : tree.fragments)
    for (const Vec3& p : f.p) {
      std::snprintf(line, sizeof line, "v %.17g %.17g %.17g\n", p.x, p.y, p.z);
      out += line;
    }
  std::size_t next = 1;
  for (const FragmentView f : tree.fragments) {
    out += "f";
    for (std::size_t i = 0; i < f.size(); ++i) {
      out += ' ';
      out += std::to_string(next++);
    }
    out += "\n";
  }
  return out;
}

// Both files or neither: the order file is written second, and the OBJ removed if that fails.
void write_both(const std::string& obj_path, const std::string& obj, const std::string& order_path,
                const std::string& order) {
  write_file_atomically(obj_path, obj);
  try {
    write_file_atomically(order_path, order);
  } catch (...) {
    std::remove(obj_path.c_str());
    throw;
  }
}

int run(Args& args) {
  std::uint64_t seed = 1;
  const bool json = args.flag("--json");
  const std::string prefix = args.required("--out");
  const std::optional<Vec3> eye_option = args.point("--eye");
  if (!eye_option) throw UsageError("missing option --eye");
  const Vec3 eye = *eye_option;
  Scene scene = scene_from_args(args, seed);
  TreeArgs t = tree_args_from(args, seed);
  t.kernel = kernel_from(args, t, scene);
  args.finish();
  nlohmann::json order = describe_run(scene, t);
  order["eye"] = {eye.x, eye.y, eye.z};
  Tree tree;
  if (t.kernel == Kernel::Exact) {
    // The eye snapped to the scene's grid, as every exact decision needs; the order is for that point.
    ExactTree exact = build_exact_from_args(scene, t);
    const auto grid_eye = snap_eye(exact.grid, eye);
    if (!grid_eye) throw UsageError("--eye is too far from the scene for its grid (more than 2^52 grid steps)");
    const Vec3 snapped = exact.grid.point(*grid_eye);
    order["eye_snapped"] = {snapped.x, snapped.y, snapped.z};
    order["back_to_front"] = exact_visibility_order(exact, *grid_eye, Order::BackToFront);
    order["exact"] = to_json(exact.exact);
    tree = std::move(exact.tree);
  } else {
    tree = build_from_args(scene, t);
    order["back_to_front"] = visibility_order(tree, eye, Order::BackToFront);
  }
  order["fragments"] = tree.fragments.size();
  const std::string obj_path = prefix + ".obj", order_path = prefix + ".order.json";
  write_both(obj_path, fragments_obj(tree), order_path, order.dump() + "\n");
  if (json) {
    std::cout << nlohmann::json{{"obj", obj_path},
                                {"order", order_path},
                                {"fragments", tree.fragments.size()},
                                {"scene_hash", order["scene_hash"]},
                                {"scene_bounds", order["scene_bounds"]}}
                     .dump()
              << "\n";
  } else {
    std::cout << "wrote " << obj_path << " and " << order_path << " (" << tree.fragments.size() << " fragments)\n";
  }
  return 0;
}

}  // namespace

Command order_command() {
  static const std::string usage =
      std::string(kSceneUsage) + " " + std::string(kTreeUsage) + " " + std::string(kKernelUsage) +
      " --eye X,Y,Z --out PREFIX [--json]";
  return {"order", usage, "write a tree's fragments (PREFIX.obj) and back-to-front order from an eye (PREFIX.order.json)",
          run,
          concat({kSceneOptions, kTreeOptions, {kKernelOption},
                  {{"--eye X,Y,Z", "the eye the order is computed for (snapped to the scene's grid with --kernel exact)"},
                   {"--out PREFIX", "writes PREFIX.obj and PREFIX.order.json"}},
                  kJsonOption})};
}

}  // namespace bsp::cli
