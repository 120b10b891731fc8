// Half of the native module's binding sources as one translation unit (the other half: bindings_a.cpp;
// core/CMakeLists.txt says why).
#include "init_frame_motion.cpp"
#include "init_render.cpp"
#include "init_render_settings.cpp"
#include "init_image.cpp"
#include "init_bsdf.cpp"
#include "init_rays.cpp"
#include "init_world_mesh.cpp"
#include "init_sky.cpp"
#include "init_denoise.cpp"
