#include "bindings.h"

#include "torrance/util/limits.h"

#include <string>

namespace torrance::python {

std::string shape_string(const py::array& a) {
  std::string s = "(";
  for (py::ssize_t i = 0; i < a.ndim(); ++i) s += (i ? ", " : "") + std::to_string(a.shape(i));
  return s + (a.ndim() == 1 ? ",)" : ")");
}

py::array numeric_array(const py::object& obj, const std::string& name, size_t itemsize) {
  const py::array raw = py::array::ensure(obj);
  if (!raw)
    throw py::type_error(name + " must be a numeric array, got " + std::string(py::str(py::type::of(obj).attr("__name__"))));
  const char kind = raw.dtype().kind();
  if (raw.size() > 0 && kind != 'b' && kind != 'i' && kind != 'u' && kind != 'f')
    throw py::type_error(name + " must hold real numbers, got dtype " + std::string(py::str(raw.dtype())));
  require_memory(double(raw.size()) * double(itemsize), name + " of shape " + shape_string(raw));
  return raw;
}

}  // namespace torrance::python
