// radchain._imaging: what radchain.render() calls (docs/python.md). A module of its own, imported on the first
// render, so that `import radchain` does not load OpenImageIO and FFTW (the command line keeps them in a module
// loaded by render/validate/mtf only, for the same reason: docs/startup.md). The pixels come from the function the
// command uses (radchain/imaging/render_request.hpp): the same request gives the same image as `radchain render …`.
#include "radchain/command_options.hpp"
#include "radchain/imaging/render_request.hpp"
#include "radchain/sensor_file.hpp"

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <variant>

namespace py = pybind11;

namespace {
using namespace radchain;

// The header as [(key, value, comment)], values as Python bool/int/float/str (FITS cards without the formatting).
py::list header_list(const render::Header& header) {
  py::list cards;
  for (const auto& card : header)
    cards.append(py::make_tuple(card.key, std::visit([](const auto& v) { return py::cast(v); }, card.value), card.comment));
  return cards;
}

// (pixels as a float32 array [row, column] with row 0 at the top, header cards, summary lines, "frame" or "scene").
py::tuple render_file(const std::string& path, const std::vector<std::pair<std::string, std::string>>& sets,
                      const std::vector<std::pair<std::string, std::string>>& options, const std::vector<std::string>& targets,
                      const std::string& scene, std::uint64_t seed, std::uint64_t star_seed) {
  render::RenderedImage r;
  {
    py::gil_scoped_release release;
    OptionValues values;
    for (const auto& [key, text] : options) values.given.emplace_back("--" + key, text);
    const Params validated = validated_options(render_option_schema(), values, "radchain.render");
    std::vector<Override> overrides;
    for (const auto& [key, text] : sets) overrides.push_back(Override{key, text});  // as radchain.load(set=…)
    Chain chain = load_sensor(path, overrides);
    const Report report = chain.run();
    r = render::render_image(chain, report, render::RenderRequest{validated, targets, scene, seed, star_seed});
  }
  py::array_t<float> pixels({r.image.height, r.image.width});
  std::copy(r.image.pixels.begin(), r.image.pixels.end(), pixels.mutable_data());
  return py::make_tuple(pixels, header_list(r.header), r.summary, r.kind == render::SensorImage::point_frame ? "frame" : "scene");
}

}  // namespace

PYBIND11_MODULE(_imaging, m) {
  m.doc() = "radchain's imaging (radchain.render): the module of the radchain package that links OpenImageIO";
  py::module_::import("radchain._radchain");  // its exception translator: InputError arrives as radchain.InputError
  m.def("render", &render_file);
}
