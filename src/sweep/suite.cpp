#include "sweep/suite.h"

#include "common/errors.h"

namespace bsp::sweep {

bool is_file_scene(std::string_view scene_name) { return scene_name.starts_with(kFileScenePrefix); }

}  // namespace bsp::sweep
