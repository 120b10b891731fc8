// Half of the native module's binding sources as one translation unit (the other half: bindings_b.cpp;
// core/CMakeLists.txt says why).
#include "module.cpp"
#include "arrays.cpp"
#include "init_scene.cpp"
#include "init_mixture.cpp"
#include "init_media.cpp"
#include "init_extra_passes.cpp"
#include "init_light_linking.cpp"
#include "init_cryptomatte.cpp"
#include "init_object_settings.cpp"
#include "init_points.cpp"
#include "init_motion.cpp"
