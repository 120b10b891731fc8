// Cryptomatte (film/cryptomatte.h): the name hash and Scene.set_cryptomatte and the objects'
// entries, bound onto the Scene class that init_scene defines.
#include "bindings.h"

#include "torrance/scene/scene.h"

#include <pybind11/stl.h>

#include <string>
#include <vector>

namespace torrance::python {

void init_cryptomatte(py::module_& m) {
  m.def(
      "cryptomatte_hash",
      [](const std::string& name) {  // a str as its UTF-8 bytes, or bytes
        const uint32_t hash = murmur_hash3(name);
        return py::make_tuple(hash, cryptomatte_float(hash));
      },
      py::arg("name"),
      "(MurmurHash3_x86_32 of `name` (UTF-8) with seed 0, that hash as Cryptomatte's float id): the manifest "
      "holds the first as 8 hex digits, the passes the second.");
  py::object cls = m.attr("Scene");
  add_method(cls,
      "set_cryptomatte",
      [](Scene& s, bool object, bool material, bool asset, int levels, std::vector<float> object_ids,
         std::vector<float> asset_ids, std::vector<float> material_ids) {
        if (asset_ids.size() != object_ids.size()) throw py::value_error("one asset id per object id");
        s.cryptomatte().set_layers(object, material, asset, levels);
        s.cryptomatte().set_objects(std::move(object_ids), std::move(asset_ids));
        s.cryptomatte().set_materials(std::move(material_ids));
      },
      py::arg("object"), py::arg("material"), py::arg("asset"), py::arg("levels"), py::arg("object_ids"),
      py::arg("asset_ids"), py::arg("material_ids"),
      "The view layer's Cryptomatte layers and Levels, the ids (cryptomatte_hash's floats) of each object entry's "
      "object and asset, and of each material. The render's passes 'cryptomatte:CryptoObject00', ... (RGBA: id, "
      "coverage, id, coverage), as Cycles writes them.");
  add_method(cls,
      "set_mesh_cryptomatte",
      [](Scene& s, uint32_t mesh, int32_t entry) { s.set_mesh_cryptomatte(mesh, entry); }, py::arg("mesh"),
      py::arg("entry"), "A mesh's object (from add_mesh) is Cryptomatte object entry `entry` (-1: none).");
  add_method(cls,
      "set_instance_cryptomatte",
      [](Scene& s, const std::vector<int64_t>& ids, int32_t entry) {
        s.set_instance_cryptomatte(ids.data(), ids.size(), entry);
      },
      py::arg("ids"), py::arg("entry"), "Instances (ids from add_instances) are Cryptomatte object entry `entry`.");
}

}  // namespace torrance::python
