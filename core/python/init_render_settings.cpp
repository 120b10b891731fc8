// RenderSettings in Python: an attribute and a constructor keyword per setting. The numbers and
// switches come from the one list, torrance/integrator/render_settings_fields.h; the settings that convert
// a string (or a list of pass names) to the core's enums and flags are bound by hand below it.
// RenderSettings.FIELDS names them all, in that order (the add-on's table is checked against it).
#include "bindings.h"

#include <pybind11/stl.h>

#include <map>
#include <string>
#include <vector>

namespace torrance::python {
namespace {

std::string model_name(BrdfModel m) {
  switch (m) {
    case BrdfModel::Paper: return "PAPER";
    case BrdfModel::Principled: return "PRINCIPLED";
    case BrdfModel::PrincipledV2: return "PRINCIPLED_V2";
  }
  return "PAPER";
}

LightSelection parse_light_selection(const std::string& s) {
  if (s == "CONTRIBUTION") return LightSelection::Contribution;
  if (s == "UNIFORM") return LightSelection::Uniform;
  if (s == "IRRADIANCE") return LightSelection::Irradiance;
  throw py::value_error("light_selection must be 'CONTRIBUTION', 'IRRADIANCE' or 'UNIFORM', got '" + s + "'");
}

std::string light_selection_name(LightSelection selection) {
  switch (selection) {
    case LightSelection::Uniform: return "UNIFORM";
    case LightSelection::Irradiance: return "IRRADIANCE";
    case LightSelection::Contribution: return "CONTRIBUTION";
  }
  return "CONTRIBUTION";
}

bool parse_sampler_is_sobol(const std::string& s) {
  if (s != "SOBOL" && s != "RANDOM") throw py::value_error("sampler must be 'SOBOL' or 'RANDOM', got '" + s + "'");
  return s == "SOBOL";
}

uint32_t parse_passes(const std::vector<std::string>& names) {
  uint32_t mask = 0;
  for (const std::string& name : names) {
    bool known = false;
    for (const PassInfo& p : kPasses)
      if (name == p.name) {
        mask |= p.pass;
        known = true;
      }
    if (!known) {
      std::string all;
      for (const PassInfo& p : kPasses) all += std::string(all.empty() ? "" : ", ") + p.name;
      throw py::value_error("unknown pass '" + name + "'; available: " + all);
    }
  }
  return mask;
}

std::vector<std::string> pass_names(uint32_t mask) {
  std::vector<std::string> names;
  for (const PassInfo& p : kPasses)
    if (mask & p.pass) names.push_back(p.name);
  return names;
}

// A C++ type of render_settings_fields.h as Python users know it.
std::string python_type(const std::string& cpp) {
  if (cpp == "int") return "int";
  if (cpp == "uint32_t") return "int in [0, 2**32)";
  if (cpp == "float" || cpp == "double") return "float";
  if (cpp == "bool") return "bool";
  if (cpp == "PixelWindow") return "None or (x0, y0, x1, y1)";
  return cpp;
}

// What each keyword of RenderSettings(...) is: its type as the error messages name it, its line
// of documentation.
struct Field {
  std::string name, type, doc;
};

// RenderSettings(**keywords): the defaults, each keyword set through its attribute (so through
// the attribute's own conversion), then validate(). A keyword of the wrong type is a TypeError
// that names it.
RenderSettings settings_from_keywords(const std::vector<Field>& fields, const py::kwargs& keywords) {
  std::map<std::string, const Field*> by_name;
  for (const Field& f : fields) by_name[f.name] = &f;
  py::object settings = py::cast(RenderSettings{});
  for (const auto& [key, value] : keywords) {
    const std::string name = py::str(key);
    const auto found = by_name.find(name);
    if (found == by_name.end())
      throw py::type_error("RenderSettings() got an unexpected keyword argument '" + name +
                           "' (RenderSettings.FIELDS lists the settings)");
    try {
      settings.attr(key) = value;
    } catch (py::error_already_set& e) {
      if (!e.matches(PyExc_TypeError)) throw;
      throw py::type_error("RenderSettings(): " + name + " must be " + found->second->type + ", got " +
                           std::string(py::str(value.get_type().attr("__name__"))));
    }
  }
  RenderSettings s = settings.cast<RenderSettings>();
  s.validate();
  return s;
}

std::string constructor_doc(const std::vector<Field>& fields) {
  const py::object defaults = py::cast(RenderSettings{});
  std::string doc =
      "RenderSettings(**settings): the core's defaults, each keyword given set as its attribute, then checked "
      "(ValueError when the settings do not make a render).\n\n";
  for (const Field& f : fields)
    doc += f.name + "=" + std::string(py::repr(defaults.attr(f.name.c_str()))) + "  (" + f.type + ") " + f.doc + "\n";
  return doc;
}

}  // namespace

void init_render_settings(py::module_& m) {
  py::class_<RenderSettings> cls(m, "RenderSettings", "What a render does (see RenderSettings.__init__).");
  std::vector<Field> fields;

#define TORRANCE_RENDER_SETTING(type, name, default_value, doc) \
  cls.def_readwrite(#name, &RenderSettings::name, doc);        \
  fields.push_back({#name, python_type(#type), doc});
#include "torrance/integrator/render_settings_fields.h"
#undef TORRANCE_RENDER_SETTING

  // Checked when set, as the constructor checks it (replaces the plain attribute of the list).
  cls.def_property(
      "first_bounce_splits", [](const RenderSettings& s) { return s.first_bounce_splits; },
      [](RenderSettings& s, int n) {
        RenderSettings checked = s;
        checked.first_bounce_splits = n;
        checked.validate();
        s.first_bounce_splits = n;
      },
      "branches at the first hit: 1 = off, 0 = automatic, 2-16 (checked when set)");

  cls.def_property(
      "brdf_model", [](const RenderSettings& s) { return model_name(s.brdf_model); },
      [](RenderSettings& s, const std::string& v) { s.brdf_model = parse_model(v); },
      "'PAPER', 'PRINCIPLED' or 'PRINCIPLED_V2'");
  fields.push_back({"brdf_model", "str", "'PAPER', 'PRINCIPLED' or 'PRINCIPLED_V2'"});
  cls.def_property(
      "light_selection", [](const RenderSettings& s) { return light_selection_name(s.light_selection); },
      [](RenderSettings& s, const std::string& v) { s.light_selection = parse_light_selection(v); },
      "'CONTRIBUTION', 'IRRADIANCE' or 'UNIFORM'");
  fields.push_back({"light_selection", "str", "'CONTRIBUTION', 'IRRADIANCE' or 'UNIFORM'"});
  cls.def_property(
      "sampler", [](const RenderSettings& s) { return std::string(s.sobol ? "SOBOL" : "RANDOM"); },
      [](RenderSettings& s, const std::string& v) { s.sobol = parse_sampler_is_sobol(v); },
      "'SOBOL' (Owen-scrambled) or 'RANDOM'");
  fields.push_back({"sampler", "str", "'SOBOL' (Owen-scrambled) or 'RANDOM'"});
  cls.def_property(
      "passes", [](const RenderSettings& s) { return pass_names(s.passes); },
      [](RenderSettings& s, const std::vector<std::string>& names) { s.passes = parse_passes(names); },
      "names of the passes rendered besides Combined (PASSES)");
  fields.push_back({"passes", "a list of str", "names of the passes rendered besides Combined (PASSES)"});

  cls.def_property_readonly("effective_adaptive_min_samples", &RenderSettings::effective_adaptive_min_samples);

  py::tuple names(fields.size());
  for (size_t i = 0; i < fields.size(); ++i) names[i] = fields[i].name;
  cls.attr("FIELDS") = names;
  cls.def(py::init([fields](const py::kwargs& keywords) { return settings_from_keywords(fields, keywords); }),
          constructor_doc(fields).c_str());
}

}  // namespace torrance::python
