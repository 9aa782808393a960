// `import pelage`: the framework from Python (pybind11). A thin client of the libraries: models
// load through scene::loadModel, fur grows through scene::growFur, every frame is played by the
// frame owner (scene::Playback), analysis, rendering and export are the same library calls the
// command line makes. Hair arrays are numpy views of pelage's buffers (no copy), kept alive by the
// arrays. The GIL is released while pelage computes. Errors: FileNotFoundError for a missing file,
// pelage.InputError (a ValueError) for a malformed file or a value out of range, ValueError for an
// unknown keyword; messages name the keyword (libraries report fields, named here as Python's).
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "convert.h"
#include "docstrings.h"
#include "pelage/animation/clip.h"
#include "pelage/fur/colors.h"
#include "pelage/fur/dynamics.h"
#include "pelage/fur/groom.h"
#include "pelage/fur/groom_strokes.h"
#include "pelage/fur/preset.h"
#include "pelage/scene/analysis_plot.h"
#include "pelage/scene/analyze.h"
#include "pelage/scene/export.h"
#include "pelage/scene/model.h"
#include "pelage/scene/playback.h"
#include "pelage/skin/subdivide.h"
#include "pelage/util/atomic_file.h"
#include "pelage/util/color.h"
#include "pelage/util/error.h"
#include "pelage/util/interrupt.h"
#include "pelage/util/log.h"
#include "pelage/util/parallel.h"
#include "pelage/util/version.h"
#ifdef PELAGE_HAVE_RENDER
#include "pelage/render/gl_context.h"
#include "pelage/render/render_sequence.h"
#endif

namespace py = pybind11;

namespace pelage::python {
namespace {

// ---- Model --------------------------------------------------------------------------------------

struct PyModel {
  std::shared_ptr<scene::Model> model;
};

PyModel load(const std::string& spec, const py::kwargs& options) {
  scene::LoadOptions opt;
  for (const auto& [k, v] : options) {
    const std::string key = py::str(k);
    if (key == "triangles") {
      opt.triangles = v.cast<int>();
    } else if (key == "unit_scale") {
      const double s = v.cast<double>();
      if (!(s > 0.0 && s <= 1e6))
        throw py::value_error("unit_scale " + py::str(v).cast<std::string>() +
                              " is out of range (0, 1000000] metres per file unit");
      opt.unitScale = static_cast<float>(s);
    } else if (key == "no_fur") {
      opt.noFurRegions = py::isinstance<py::str>(v)
                             ? std::vector<std::string>{v.cast<std::string>()}
                             : v.cast<std::vector<std::string>>();
    } else if (key == "directions") {
      opt.segmentDirections = v.cast<std::string>();
    } else if (key == "subdivide") {
      const bool isAuto = py::isinstance<py::str>(v) && v.cast<std::string>() == "auto";
      if (!isAuto && (!py::isinstance<py::int_>(v) || v.cast<long long>() < 0 ||
                      v.cast<long long>() > skin::kMaxSubdivisionLevels))
        throw py::value_error("subdivide " + py::repr(v).cast<std::string>() +
                              " is not 'auto' or a level in [0, 3]");
      opt.subdivide = isAuto ? -1 : v.cast<int>();
    } else {
      badKeyword("load", key, {"triangles", "unit_scale", "no_fur", "directions", "subdivide"});
    }
  }
  PyModel m;
  {
    py::gil_scoped_release release;
    m.model = std::make_shared<scene::Model>(scene::loadModel(spec, opt));
  }
  return m;
}

// The clip index for `clip` (None: -1, the still pose).
int clipIndex(scene::Model& model, const py::object& clip) {
  if (clip.is_none()) return -1;
  return scene::resolveClip(model, clip.cast<std::string>());
}

// ---- Fur ----------------------------------------------------------------------------------------

struct PyFur {
  std::shared_ptr<scene::Model> model;
  std::shared_ptr<const scene::Fur> fur;
};

// `preset` with every keyword set as its preset-file field (nested objects field by field).
fur::FurParams furParams(const std::string& preset, const py::kwargs& fields) {
  const fur::FurParams base = fur::loadFurPreset(preset);
  if (fields.empty()) return base;
  nlohmann::json doc = nlohmann::json::object();
  for (const auto& [k, v] : fields) doc[py::str(k).cast<std::string>()] = toJson(v);
  return fur::applyFurPresetFields(base, doc.dump(), "fur()");
}

// Model.write_groom: numpy arrays (convert.h) and grooming strokes (a strokes file's path or its
// JSON as a dict) into a groom file, checked by its reader before anything is written.
void writeGroom(const PyModel& m, const std::string& path, const py::object& length,
                const py::object& density, const py::object& tint, const py::object& comb,
                const py::object& clump, const py::object& stiffness,
                const py::object& segmentDirectionWeight, const py::object& curlRadius,
                const py::object& curlTurns, const py::object& widthScale,
                const py::object& colorSourceWeight, const py::object& strokes) {
  const skin::SkinMesh& skin = m.model->skin;
  fur::VertexGroom g =
      vertexGroomFrom(skin.numVertices(), length, density, tint, comb, clump, stiffness,
                      segmentDirectionWeight, curlRadius, curlTurns, widthScale, colorSourceWeight);
  if (!strokes.is_none())
    fur::applyGroomStrokes(skin,
                           py::isinstance<py::str>(strokes)
                               ? fur::readGroomStrokes(strokes.cast<std::string>())
                               : fur::parseGroomStrokes(toJson(strokes).dump(), "strokes"),
                           g);
  const std::string text = fur::groomFileJson(skin, g);
  (void)fur::parseGroomFile(text, path, skin, m.model->name);
  writeFileAtomically(path, text);
}

// The fur of `furArg` (None: the default preset's), which must have grown on `model`.
std::shared_ptr<const scene::Fur> furOf(const PyModel& m, const py::object& furArg) {
  if (furArg.is_none()) {
    py::gil_scoped_release release;
    return std::make_shared<scene::Fur>(scene::growFur(*m.model, fur::loadFurPreset("default")));
  }
  const PyFur& f = furArg.cast<const PyFur&>();
  if (f.model != m.model)
    throw py::value_error("fur: grew on another model (use model.fur(...) of this model)");
  return f.fur;
}

// ---- Hairs --------------------------------------------------------------------------------------

// One frame's hairs: the frame's buffers (both coats, one allocation), and per hair its coat, root
// index, triangle and barycentric coordinates.
struct PyHairs {
  std::shared_ptr<const scene::Fur> fur;  // the roots the hairs grew from
  fur::FurFrame frame;
  std::vector<std::uint8_t> coat;
  std::vector<std::int32_t> hair, triangle;
  std::vector<float> barycentric;    // n x 3
  std::vector<std::uint8_t> colors;  // n x 2 x 3: root and tip, 8-bit sRGB
  int clip = -1;
  int frameNumber = 0;
  double seconds = 0.0;

  std::int64_t count() const { return frame.drawn(); }
  void index() {
    const std::int64_t n = count();
    coat.resize(static_cast<std::size_t>(n));
    hair.resize(static_cast<std::size_t>(n));
    triangle.resize(static_cast<std::size_t>(n));
    barycentric.resize(static_cast<std::size_t>(3 * n));
    colors.resize(static_cast<std::size_t>(6 * n));
    std::size_t i = 0;
    for (int c = 0; c < fur::kCoatCount; ++c) {
      const fur::HairBuffers& b = frame.coats[static_cast<std::size_t>(c)];
      const fur::CoatRoots& cr = fur->roots.coats[static_cast<std::size_t>(c)];
      for (std::int64_t h = 0; h < b.drawn; ++h, ++i) {
        const auto r = static_cast<std::size_t>(b.hairIds[static_cast<std::size_t>(h)]);
        coat[i] = static_cast<std::uint8_t>(c);
        hair[i] = static_cast<std::int32_t>(r);
        triangle[i] = cr.triangle[r];
        const float* bc = fur->roots.barycentric.data() + 4 * cr.tableIndex[r];
        std::copy(bc, bc + 3, barycentric.begin() + static_cast<std::ptrdiff_t>(3 * i));
        const fur::CoatColors& cc = fur->colors.coats[static_cast<std::size_t>(c)];
        for (int end = 0; end < 2; ++end) {
          const std::uint32_t packed = cc.perHair ? b.colors[static_cast<std::size_t>(2 * h + end)]
                                                  : fur::packSrgb8(cc.diffuse);
          for (int k = 0; k < 3; ++k)
            colors[6 * i + static_cast<std::size_t>(3 * end + k)] =
                static_cast<std::uint8_t>(packed >> (8 * k));
        }
      }
    }
  }
  // Both coats as one (n, P, 3) array: their points per hair must agree, and coat 0's hairs end
  // where coat 1's begin (every root drawn).
  int commonPoints() const {
    const fur::HairBuffers& a = frame.coats[0];
    const fur::HairBuffers& b = frame.coats[1];
    if (a.drawn > 0 && b.drawn > 0 && a.layout.pointsPerHair() != b.layout.pointsPerHair())
      throw py::value_error(
          "the coats have " + std::to_string(a.layout.pointsPerHair()) + " and " +
          std::to_string(b.layout.pointsPerHair()) +
          " points per hair (different styles): use coat_points(c) and coat_normals(c)");
    return a.drawn > 0 ? a.layout.pointsPerHair() : b.layout.pointsPerHair();
  }
};

py::array_t<float> view3(const float* data, std::int64_t hairs, int points, py::handle owner) {
  const auto P = static_cast<py::ssize_t>(points);
  return py::array_t<float>({static_cast<py::ssize_t>(hairs), P, py::ssize_t{3}},
                            {P * 3 * 4, py::ssize_t{12}, py::ssize_t{4}}, data, owner);
}

// `v` as an (n,) array (columns 1) or (n, columns), a view kept alive by `owner`.
template <typename T>
py::array_t<T> rowsView(std::vector<T>& v, int columns, py::handle owner) {
  const auto n = static_cast<py::ssize_t>(v.size() / static_cast<std::size_t>(columns));
  const auto s = static_cast<py::ssize_t>(sizeof(T));
  if (columns == 1) return py::array_t<T>({n}, {s}, v.data(), owner);
  return py::array_t<T>({n, py::ssize_t{columns}}, {s * columns, s}, v.data(), owner);
}

// Coat c's points (member &HairBuffers::positions) or normals as an (n_c, P_c, 3) view.
py::array_t<float> coatView(py::object self, int c, fur::FloatSpan fur::HairBuffers::*member) {
  PyHairs& h = self.cast<PyHairs&>();
  if (c < 0 || c > 1) throw py::value_error("coat " + std::to_string(c) + " (accepted: 0, 1)");
  const fur::HairBuffers& b = h.frame.coats[static_cast<std::size_t>(c)];
  return view3((b.*member).data(), b.drawn, b.layout.pointsPerHair(), self);
}

// Hairs of the frame the playback has posed and evaluated, taken out of it.
std::shared_ptr<PyHairs> takeHairs(scene::Playback& playback, std::shared_ptr<const scene::Fur> fur,
                                   int frame) {
  auto h = std::make_shared<PyHairs>();
  h->fur = std::move(fur);
  playback.takeHairs(h->frame);
  h->index();
  h->clip = playback.options().clip;
  h->frameNumber = frame;
  h->seconds = playback.options().clock.secondsAt(frame);
  return h;
}

// The playback options of a clip (or None) at `time` (a sequence's frame 0 is at `time`).
scene::PlaybackOptions playbackOptions(scene::Model& model, const py::object& clip, double time,
                                       double fps, const Dynamics& dyn) {
  scene::PlaybackOptions po;
  po.clip = clipIndex(model, clip);
  po.clock.fps = fps;
  po.clock.startSeconds = time;
  po.hairSource = scene::HairSource::Cpu;
  po.dynamics = dyn.on;
  po.dynamicsParams = dyn.params;
  po.clock.preRollFrames = dyn.preRoll;
  return po;
}

std::shared_ptr<PyHairs> hairsOf(const PyFur& f, const py::object& clip, double time,
                                 const py::object& dynamics, double fps) {
  const Dynamics dyn = dynamicsFrom(dynamics);
  scene::PlaybackOptions po = playbackOptions(*f.model, clip, 0.0, fps, dyn);
  if (po.clip < 0 && time != 0.0) throw py::value_error("time needs a clip");
  // As `pelage hair`: the clip at `time`, or with dynamics its frames from its start up to `time`.
  const int frame = scene::oneFrameAt(po, time);
  std::shared_ptr<PyHairs> h;
  {
    py::gil_scoped_release release;
    scene::Playback playback(*f.model, *f.fur, po);
    playback.poseFrame(frame);
    playback.evaluateFur(fur::FurView{});
    h = takeHairs(playback, f.fur, frame);
  }
  flushWarnings();
  return h;
}

// Fur.frames(): the frames in order, the dynamic springs stepping from one to the next.
struct FrameIterator {
  PyFur fur;
  std::unique_ptr<scene::Playback> playback;
  scene::FrameRange range;
  int next = 0;
  std::shared_ptr<PyHairs> step() {
    if (next > range.last) throw py::stop_iteration();
    const int f = next;
    next += range.step;
    std::shared_ptr<PyHairs> h;
    {
      py::gil_scoped_release release;
      playback->poseFrame(f);
      playback->evaluateFur(fur::FurView{});
      h = takeHairs(*playback, fur.fur, f);
    }
    flushWarnings();
    return h;
  }
};

// ---- Analysis -----------------------------------------------------------------------------------

py::dict analyze(PyModel& m, const py::object& clip, const py::object& furArg,
                 const py::kwargs& kwargs) {
  const Keywords kw("analyze", kwargs,
                    {"frames", "dynamics", "hold", "groups", "fps", "time", "sweep", "plot"});
  scene::Model& model = *m.model;
  const std::shared_ptr<const scene::Fur> fur = furOf(m, furArg);
  const Dynamics dyn = dynamicsFrom(kw.object("dynamics"));
  const double fps = kw.get("fps", 30.0);
  scene::AnalysisOptions opt;
  opt.clip = clipIndex(model, clip);
  opt.clock.fps = fps;  // (analyzeClip checks the values)
  opt.clock.startSeconds = kw.get("time", 0.0);
  opt.clock.preRollFrames = dyn.preRoll;
  opt.dynamics = dyn.on;
  opt.dynamicsParams = dyn.params;
  opt.holdSeconds = kw.get("hold", 0.0);
  opt.groups = scene::parseAnalysisGroups(kw.get<std::string>("groups", "region"));
  opt.frames = frameRange(kw.object("frames"), scene::wholeClip(model, opt.clip, fps));
  const std::string plot = kw.get<std::string>("plot", "");
  if (!plot.empty()) scene::validatePlotFile(plot);
  scene::AnalysisTable table;
  const py::object sweep = kw.object("sweep");
  if (!sweep.is_none()) {
    const scene::SweepSpec spec = sweepOf(sweep);
    // The plot's title says the sweep as it was given (the command line's text), or its parameter.
    const std::string sweepText =
        py::isinstance<py::str>(sweep) ? sweep.cast<std::string>() : spec.parameter;
    py::gil_scoped_release release;
    const scene::SweepResult result = scene::sweepClip(model, *fur, opt, spec);
    table = scene::sweepTable(result);
    if (!plot.empty())
      scene::writePlotPng(plot, scene::sweepPlot(result, scene::analysisTitle(model, *fur, opt) +
                                                             ", sweep " + sweepText));
  } else {
    py::gil_scoped_release release;
    const scene::AnalysisResult result = scene::analyzeClip(model, *fur, opt);
    table = scene::analysisTable(result);
    if (!plot.empty())
      scene::writePlotPng(plot,
                          scene::analysisPlot(result, scene::analysisTitle(model, *fur, opt)));
  }
  flushWarnings();
  return columns(table);
}

// ---- Export -------------------------------------------------------------------------------------

std::vector<std::string> exportFrames(PyModel& m, const py::object& clip, const py::object& furArg,
                                      const py::kwargs& kwargs) {
  const Keywords kw("export", kwargs,
                    {"out", "frames", "format", "fps", "time", "dynamics", "resume"});
  if (!kwargs.contains("out"))
    throw py::value_error(
        "export(): out is required (the directory for the frames, or the "
        ".usda file)");
  scene::Model& model = *m.model;
  const std::shared_ptr<const scene::Fur> fur = furOf(m, furArg);
  scene::ExportOptions eo;
  eo.format = scene::parseExportFormat(kw.get<std::string>("format", "ply"));
  eo.out = py::str(kw.object("out")).cast<std::string>();  // a str or a pathlib.Path
  eo.resume = kw.get("resume", false);
  const double fps = kw.get("fps", 30.0);
  const Dynamics dyn = dynamicsFrom(kw.object("dynamics"));
  eo.playback = playbackOptions(model, clip, kw.get("time", 0.0), fps, dyn);
  eo.frames = frameRange(kw.object("frames"), scene::wholeClip(model, eo.playback.clip, fps));
  scene::ExportReport r;
  {
    py::gil_scoped_release release;
    r = scene::exportClip(model, *fur, eo);
  }
  flushWarnings();
  return r.files;
}

// ---- Render -------------------------------------------------------------------------------------

#ifdef PELAGE_HAVE_RENDER
// A sequence of three numbers as (r, g, b); ValueError naming `keyword` with `accepted` otherwise.
Eigen::Vector3f rgbOf(const py::object& value, const char* keyword, const char* accepted) {
  std::vector<float> c;
  try {
    c = value.cast<std::vector<float>>();
  } catch (const py::cast_error&) {
  }
  if (c.size() != 3) throw py::value_error(std::string(keyword) + ": " + accepted);
  return {c[0], c[1], c[2]};
}

// An (r, g, b) colour, each in [0, 1] (scene::validateColor names `keyword`).
Eigen::Vector3f colorOf(const py::object& value, const char* keyword) {
  const Eigen::Vector3f rgb = rgbOf(value, keyword, "three values (r, g, b), each in [0, 1]");
  scene::validateColor(rgb, keyword);
  return rgb;
}

// render()'s light_color and ambient: one intensity (grey) or (r, g, b), linear, each in [0, 16].
Eigen::Vector3f intensityOf(const py::object& value, const char* keyword) {
  const Eigen::Vector3f rgb =
      py::isinstance<py::float_>(value) || py::isinstance<py::int_>(value)
          ? Eigen::Vector3f::Constant(value.cast<float>())
          : rgbOf(value, keyword,
                  "one intensity or three values (r, g, b), linear, each in [0, 16]");
  scene::validateLightIntensity(rgb, keyword);
  return rgb;
}

// render()'s background: None (the default colour, opaque), "transparent" (straight alpha), or an
// (r, g, b) sRGB colour in [0, 1]; returns whether it is transparent.
bool backgroundOf(const py::object& background, render::SequenceOptions& o) {
  if (background.is_none()) return false;
  if (py::isinstance<py::str>(background)) {
    if (background.cast<std::string>() == "transparent") return true;
    throw py::value_error("background: 'transparent' or (r, g, b) in [0, 1], got '" +
                          excerpt(background.cast<std::string>()) + "'");
  }
  o.look.background = srgbToLinear(colorOf(background, "background"));
  return false;
}

py::array_t<std::uint8_t> renderFrame(PyModel& m, const py::object& clip, const py::object& furArg,
                                      const py::kwargs& kwargs) {
  const Keywords kw("render", kwargs,
                    {"frame",        "fps",        "time",           "size",        "camera",
                     "fov",          "follow",     "hair_source",    "shading",     "lines",
                     "transparency", "shadows",    "self_shadowing", "samples",     "dynamics",
                     "skin_color",   "background", "light",          "light_color", "ambient"});
  scene::Model& model = *m.model;
  const std::shared_ptr<const scene::Fur> fur = furOf(m, furArg);
  render::SequenceOptions o;
  const Dynamics dyn = dynamicsFrom(kw.object("dynamics"));
  o.playback = playbackOptions(model, clip, kw.get("time", 0.0), kw.get("fps", 30.0), dyn);
  o.playback.hairSource = scene::parseHairSource(kw.get<std::string>("hair_source", "gpu"));
  const int frame = kw.get("frame", 0);
  o.frames = {frame, frame};
  const auto size = kw.get("size", std::pair<int, int>(1280, 720));
  o.width = size.first;
  o.height = size.second;
  o.samples = kw.get("samples", -1);
  o.camera.preset = scene::parseCameraPreset(kw.get<std::string>("camera", "three-quarter"));
  o.camera.fovYDegrees = static_cast<float>(kw.get("fov", double{scene::kDefaultFovYDegrees}));
  o.camera.track = kw.get("follow", false);
  o.look.hairShading = scene::parseHairShading(kw.get<std::string>(
      "shading", std::string(scene::hairShadingName(scene::kDefaultHairShading))));
  o.look.hairWidth = kw.get("lines", false) ? scene::HairWidth::Lines : scene::HairWidth::Strands;
  o.look.transparency = kw.get("transparency", true);
  o.shadows = kw.get("shadows", false);
  o.selfShadowing = kw.get("self_shadowing", true);
  const auto light = kw.get("light", std::pair<float, float>(scene::kKeyLightAzimuthDegrees,
                                                             scene::kKeyLightElevationDegrees));
  o.lightAzimuth = light.first;
  o.lightElevation = light.second;
  if (const py::object c = kw.object("light_color"); !c.is_none())
    o.lightColor = intensityOf(c, "light_color");
  if (const py::object a = kw.object("ambient"); !a.is_none())
    o.ambient = intensityOf(a, "ambient");
  o.transparentBackground = backgroundOf(kw.object("background"), o);
  const py::object skinColor = kw.object("skin_color");
  if (!skinColor.is_none()) o.skinColor = colorOf(skinColor, "skin_color");
  o.outDir = ".";  // (nothing is written)
  render::validateSequenceOptions(o);
  render::Image image;
  {
    py::gil_scoped_release release;
    auto context = render::createHeadlessContext();
    render::SequenceRenderer renderer(model, *fur, o);
    renderer.render(frame, image);
  }
  flushWarnings();
  const int channels = o.transparentBackground ? 4 : 3;
  py::array_t<std::uint8_t> pixels({static_cast<py::ssize_t>(image.height),
                                    static_cast<py::ssize_t>(image.width),
                                    static_cast<py::ssize_t>(channels)});
  auto out = pixels.mutable_unchecked<3>();
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      const std::uint8_t* p = image.pixel(x, y);
      for (int c = 0; c < channels; ++c) out(y, x, c) = p[c];
    }
  return pixels;
}
#endif

}  // namespace
}  // namespace pelage::python

PYBIND11_MODULE(_pelage, m) {
  using namespace pelage;
  using namespace pelage::python;
  m.doc() = "pelage: animated furred creatures (Van Gelder & Wilhelms 1997 fur model)";
  m.attr("__version__") = util::kVersion;  // CMake's project(VERSION), as `pelage --version`

  // pelage's warnings become Python warnings (UserWarning), Ctrl-C a KeyboardInterrupt within a
  // frame of any long call.
  setWarningSink(queueWarning);
  setInterruptPoll(pollPython);

  static py::exception<InputError> inputError(m, "InputError", PyExc_ValueError);
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const MissingFileError& e) {
      PyErr_SetString(PyExc_FileNotFoundError, e.what());
    } catch (const InputError& e) {
      PyErr_SetString(inputError.ptr(), pythonMessage(e).c_str());
    } catch (const Interrupted&) {
      PyErr_SetNone(PyExc_KeyboardInterrupt);
    }
  });

  // Every class is declared before the functions that take or return it, so that signatures
  // show their Python names (pelage.Hairs, not the C++ type).
  py::class_<PyModel> model(m, "Model", doc::kModelDoc);
  py::class_<PyFur> furClass(m, "Fur", doc::kFurDoc);
  py::class_<PyHairs, std::shared_ptr<PyHairs>> hairs(
      m, "Hairs",
      "One frame's hairs; every array is a view of pelage's buffers and keeps them alive.");
  py::class_<FrameIterator, std::shared_ptr<FrameIterator>> frameIterator(
      m, "FrameIterator", "The frames of a clip in order (Fur.frames()), one Hairs each.");

  m.def(
      "set_threads",
      [](int n) {
        if (n < 0 || n > 1024)
          throw py::value_error("threads " + std::to_string(n) + " is out of range [0, 1024]");
        setThreadCount(n);
      },
      py::arg("n"), doc::kSetThreadsDoc);
  m.def(
      "threads", [] { return threadCount(); }, "The worker thread count in use (an int).");

  model
      .def_property_readonly(
          "name", [](const PyModel& s) { return s.model->name; }, "The creature's name (str).")
      .def_property_readonly(
          "source", [](const PyModel& s) { return s.model->source; },
          "Where it was loaded from (str).")
      .def_property_readonly(
          "segments",
          [](const PyModel& s) {
            std::vector<std::string> names;
            for (const auto& seg : s.model->body.segments) names.push_back(seg.name);
            return names;
          },
          "The body's segment names (list of str), parents before children.")
      .def_property_readonly(
          "regions", [](const PyModel& s) { return s.model->skin.regionNames; },
          "The skin's region names (list of str): groups of analyze() and patterns of no_fur.")
      .def_property_readonly(
          "clips",
          [](const PyModel& s) {
            py::dict d;
            for (const auto& c : s.model->clips) d[py::str(c.name)] = shortestDouble(c.duration);
            return d;
          },
          "The clips (dict): name -> duration in seconds.")
      .def(
          "skin",
          [](PyModel& s, const py::object& clip, double time) {
            scene::PlaybackOptions po = playbackOptions(*s.model, clip, time, 30.0, Dynamics{});
            std::vector<float> pos, nrm;
            {
              py::gil_scoped_release release;
              const scene::Fur none;  // the skin only
              scene::Playback playback(*s.model, none, po);
              playback.poseFrame(0);
              for (const auto& p : playback.state().skin.positions)
                pos.insert(pos.end(), {p.x(), p.y(), p.z()});
              for (const auto& n : playback.state().skin.normals)
                nrm.insert(nrm.end(), {n.x(), n.y(), n.z()});
            }
            flushWarnings();
            const auto nV = static_cast<py::ssize_t>(pos.size() / 3);
            const auto& tri = s.model->skin.triangles;
            return py::make_tuple(
                py::array_t<float>({nV, py::ssize_t{3}}, pos.data()),
                py::array_t<float>({nV, py::ssize_t{3}}, nrm.data()),
                py::array_t<std::int32_t>(
                    {static_cast<py::ssize_t>(tri.size() / 3), py::ssize_t{3}}, tri.data()));
          },
          py::arg("clip") = py::none(), py::arg("time") = 0.0, doc::kSkinDoc)
      .def(
          "fur",
          [](PyModel& s, const std::string& preset, const py::kwargs& fields) {
            const fur::FurParams params = furParams(preset, fields);
            PyFur f;
            f.model = s.model;
            {
              py::gil_scoped_release release;
              f.fur = std::make_shared<scene::Fur>(scene::growFur(*s.model, params));
            }
            flushWarnings();
            return f;
          },
          py::arg("preset") = "default", doc::kGrowFurDoc)
      .def("write_groom", &writeGroom, py::arg("path"), py::arg("length") = py::none(),
           py::arg("density") = py::none(), py::arg("tint") = py::none(),
           py::arg("comb") = py::none(), py::arg("clump") = py::none(),
           py::arg("stiffness") = py::none(), py::arg("segment_direction_weight") = py::none(),
           py::arg("curl_radius") = py::none(), py::arg("curl_turns") = py::none(),
           py::arg("width_scale") = py::none(), py::arg("color_source_weight") = py::none(),
           py::arg("strokes") = py::none(), doc::kWriteGroomDoc)
      .def("__repr__", [](const PyModel& s) {
        return "<pelage.Model " + s.model->name + ": " + std::to_string(s.model->body.size()) +
               " segments, " + std::to_string(s.model->skin.numTriangles()) + " triangles, " +
               std::to_string(s.model->clips.size()) + " clips>";
      });

  furClass
      .def_property_readonly(
          "params",
          [](const PyFur& f) {
            return fromJson(nlohmann::json::parse(fur::furPresetJson(f.fur->params)));
          },
          "The parameters (dict), as the preset file's fields.")
      .def_property_readonly(
          "groom", [](const PyFur& f) { return groomDict(f.fur->groom.vertex); },
          "The per-vertex groom the hairs grew from (dict of numpy arrays: "
          "'length' (nV,) metres, 'density' (nV,), 'tint' (nV, 3), 'comb' (nV, 3), 'clump' (nV,), "
          "'stiffness', 'segment_direction_weight', 'curl_radius', 'curl_turns' and "
          "'width_scale' (nV, 2), 'color_source_weight' (a dict of the five colour sources "
          "to (nV, 2)) "
          "(overcoat, undercoat); "
          "only those "
          "a groom file or the regions set).")
      .def_property_readonly(
          "roots", [](const PyFur& f) { return f.fur->roots.total(); },
          "Hairs grown, both coats (int).")
      .def("hairs", &hairsOf, py::arg("clip") = py::none(), py::arg("time") = 0.0,
           py::arg("dynamics") = py::none(), py::arg("fps") = 30.0, doc::kHairsDoc)
      .def(
          "frames",
          [](const PyFur& f, const py::object& clip, double fps, const py::object& frames,
             const py::object& dynamics, double time) {
            auto it = std::make_shared<FrameIterator>();
            it->fur = f;
            const Dynamics dyn = dynamicsFrom(dynamics);
            scene::PlaybackOptions po = playbackOptions(*f.model, clip, time, fps, dyn);
            it->range = frameRange(frames, scene::wholeClip(*f.model, po.clip, fps));
            it->next = it->range.first;
            py::gil_scoped_release release;
            it->playback = std::make_unique<scene::Playback>(*f.model, *f.fur, po);
            return it;
          },
          py::arg("clip"), py::arg("fps") = 30.0, py::arg("frames") = py::none(),
          py::arg("dynamics") = py::none(), py::arg("time") = 0.0, doc::kFramesDoc);

  frameIterator.def("__iter__", [](std::shared_ptr<FrameIterator> self) { return self; })
      .def("__next__", &FrameIterator::step);

  hairs.def("__len__", &PyHairs::count)
      .def_property_readonly(
          "frame", [](const PyHairs& h) { return h.frameNumber; }, "The frame number (int).")
      .def_property_readonly(
          "time", [](const PyHairs& h) { return h.seconds; }, "The clip time, seconds (float).")
      .def_property_readonly(
          "points",
          [](py::object self) {
            PyHairs& h = self.cast<PyHairs&>();
            return view3(h.frame.positions.data(), h.count(), h.commonPoints(), self);
          },
          "(n, P, 3) float32: each hair's points, root first, metres (both coats: overcoat first)")
      .def_property_readonly(
          "normals",
          [](py::object self) {
            PyHairs& h = self.cast<PyHairs&>();
            return view3(h.frame.normals.data(), h.count(), h.commonPoints(), self);
          },
          "(n, P, 3) float32: the style's shading normal at each point")
      .def(
          "coat_points",
          [](py::object self, int c) { return coatView(self, c, &fur::HairBuffers::positions); },
          py::arg("coat"), "(n_c, P_c, 3) float32: coat c's points (0 overcoat, 1 undercoat)")
      .def(
          "coat_normals",
          [](py::object self, int c) { return coatView(self, c, &fur::HairBuffers::normals); },
          py::arg("coat"), "(n_c, P_c, 3) float32: coat c's normals")
      .def_property_readonly(
          "coat", [](py::object self) { return rowsView(self.cast<PyHairs&>().coat, 1, self); },
          "(n,) uint8: 0 overcoat, 1 undercoat")
      .def_property_readonly(
          "hair", [](py::object self) { return rowsView(self.cast<PyHairs&>().hair, 1, self); },
          "(n,) int32: the hair's root index in its coat")
      .def_property_readonly(
          "triangle",
          [](py::object self) { return rowsView(self.cast<PyHairs&>().triangle, 1, self); },
          "(n,) int32: the skin triangle of the root")
      .def_property_readonly(
          "barycentric",
          [](py::object self) { return rowsView(self.cast<PyHairs&>().barycentric, 3, self); },
          "(n, 3) float32: the root's barycentric coordinates in its triangle (sec. 3.2)")
      .def_property_readonly(
          "colors",
          [](py::object self) {
            PyHairs& h = self.cast<PyHairs&>();
            return py::array_t<std::uint8_t>(
                {static_cast<py::ssize_t>(h.count()), py::ssize_t{2}, py::ssize_t{3}},
                {py::ssize_t{6}, py::ssize_t{3}, py::ssize_t{1}}, h.colors.data(), self);
          },
          "(n, 2, 3) uint8: each hair's root and tip colour, 8-bit sRGB (its points are graded "
          "between them, in linear light)")
      .def_property_readonly(
          "styles",
          [](const PyHairs& h) {
            return py::make_tuple(fur::styleName(h.frame.coats[0].layout.style),
                                  fur::styleName(h.frame.coats[1].layout.style));
          },
          "(overcoat, undercoat) style names (tuple of str).");

  m.def("load", &load, py::arg("model") = "monkey", doc::kLoadDoc);
  m.def("analyze", &analyze, py::arg("model"), py::arg("clip") = py::none(),
        py::arg("fur") = py::none(), doc::kAnalyzeDoc);
  m.def("export", &exportFrames, py::arg("model"), py::arg("clip") = py::none(),
        py::arg("fur") = py::none(), doc::kExportDoc);
#ifdef PELAGE_HAVE_RENDER
  m.def("render", &renderFrame, py::arg("model"), py::arg("clip") = py::none(),
        py::arg("fur") = py::none(), doc::kRenderDoc);
#endif
}
