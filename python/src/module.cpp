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
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "pelage/animation/clip.h"
#include "pelage/fur/colors.h"
#include "pelage/fur/dynamics.h"
#include "pelage/fur/preset.h"
#include "pelage/scene/analyze.h"
#include "pelage/scene/export.h"
#include "pelage/scene/model.h"
#include "pelage/scene/playback.h"
#include "pelage/util/error.h"
#include "pelage/util/parallel.h"
#ifdef PELAGE_HAVE_RENDER
#include "pelage/viewer/gl_context.h"
#include "pelage/viewer/render_sequence.h"
#endif

namespace py = pybind11;

namespace pelage::python {
namespace {

// ---- Errors -------------------------------------------------------------------------------------

// A library error in Python's words: a field ("hair source") becomes the keyword (hair_source).
std::string pythonMessage(const InputError& e) {
  if (e.field().empty()) return e.what();
  std::string keyword = e.field();
  std::replace(keyword.begin(), keyword.end(), ' ', '_');
  return InputError::join(keyword, e.detail());
}

[[noreturn]] void badKeyword(const std::string& function, const std::string& key,
                             const std::vector<std::string>& accepted) {
  std::string list;
  for (const std::string& a : accepted) list += (list.empty() ? "" : ", ") + a;
  throw py::value_error(function + "(): unknown keyword '" + key + "' (accepted: " + list + ")");
}

// ---- Conversions --------------------------------------------------------------------------------

nlohmann::json toJson(const py::handle& value) {
  if (value.is_none()) return nullptr;
  if (py::isinstance<py::bool_>(value)) return value.cast<bool>();
  if (py::isinstance<py::int_>(value)) return value.cast<long long>();
  if (py::isinstance<py::float_>(value)) return value.cast<double>();
  if (py::isinstance<py::str>(value)) return value.cast<std::string>();
  if (py::isinstance<py::dict>(value)) {
    nlohmann::json j = nlohmann::json::object();
    for (const auto& [k, v] : value.cast<py::dict>()) j[py::str(k).cast<std::string>()] = toJson(v);
    return j;
  }
  if (py::isinstance<py::sequence>(value)) {
    nlohmann::json j = nlohmann::json::array();
    for (const auto& v : value.cast<py::sequence>()) j.push_back(toJson(v));
    return j;
  }
  if (py::hasattr(value, "tolist")) return toJson(value.attr("tolist")());
  throw py::value_error("cannot use a " + py::str(value.get_type()).cast<std::string>() +
                        " as a fur parameter value");
}

// A float32 value as the double Python prints as the float's shortest decimal (0.3f -> 0.3, not
// 0.30000001192092896); other doubles unchanged.
double shortestDouble(double d) {
  const auto f = static_cast<float>(d);
  if (!std::isfinite(d) || static_cast<double>(f) != d) return d;
  char text[32];
  const auto r = std::to_chars(text, text + sizeof text, f);
  return std::strtod(std::string(text, r.ptr).c_str(), nullptr);
}

py::object fromJson(const nlohmann::json& j) {
  if (j.is_null()) return py::none();
  if (j.is_boolean()) return py::bool_(j.get<bool>());
  if (j.is_number_integer()) return py::int_(j.get<long long>());
  if (j.is_number()) return py::float_(shortestDouble(j.get<double>()));
  if (j.is_string()) return py::str(j.get<std::string>());
  if (j.is_array()) {
    py::list l;
    for (const auto& v : j) l.append(fromJson(v));
    return l;
  }
  py::dict d;
  for (auto it = j.begin(); it != j.end(); ++it) d[py::str(it.key())] = fromJson(it.value());
  return d;
}

// The frames of `frames`: None (the default of `fallback`), an int, a (first, last) pair, or a
// range with step 1.
scene::FrameRange frameRange(const py::object& frames, const scene::FrameRange& fallback) {
  if (frames.is_none()) return fallback;
  scene::FrameRange r;
  if (py::isinstance<py::int_>(frames)) {
    r.first = r.last = frames.cast<int>();
  } else if (py::isinstance(frames, py::module_::import("builtins").attr("range"))) {
    const int start = frames.attr("start").cast<int>(), stop = frames.attr("stop").cast<int>();
    if (frames.attr("step").cast<int>() != 1 || stop <= start)
      throw py::value_error("frames: a range of step 1 with at least one frame is needed");
    r.first = start;
    r.last = stop - 1;
  } else {
    const auto pair = frames.cast<std::vector<int>>();
    if (pair.size() != 2) throw py::value_error("frames: an int, a (first, last) pair or a range");
    r.first = pair[0];
    r.last = pair[1];
  }
  // The one frame-range rule (and its message).
  return scene::parseFrameRange(std::to_string(r.first) + ":" + std::to_string(r.last));
}

// Dynamic fur from `dynamics`: None or False (off), True (the defaults), or a dict with
// "frequency" and "damping" (one value or one per coat) and "preroll".
struct Dynamics {
  bool on = false;
  fur::DynamicsParams params;
  int preRoll = -1;
};
Dynamics dynamicsFrom(const py::object& d) {
  Dynamics out;
  if (d.is_none()) return out;
  if (py::isinstance<py::bool_>(d)) {
    out.on = d.cast<bool>();
    return out;
  }
  out.on = true;
  for (const auto& [k, v] : d.cast<py::dict>()) {
    const std::string key = py::str(k);
    if (key == "frequency" || key == "damping") {
      std::vector<double> values;
      if (py::isinstance<py::float_>(v) || py::isinstance<py::int_>(v))
        values = {v.cast<double>()};
      else
        values = v.cast<std::vector<double>>();
      if (values.empty() || values.size() > 2)
        throw py::value_error("dynamics['" + key + "']: one value, or one per coat (two)");
      for (int c = 0; c < fur::kCoatCount; ++c) {
        const double x =
            values[std::min<std::size_t>(static_cast<std::size_t>(c), values.size() - 1)];
        if (key == "frequency")
          out.params.coats[static_cast<std::size_t>(c)].frequencyHz = static_cast<float>(x);
        else
          out.params.coats[static_cast<std::size_t>(c)].dampingRatio = static_cast<float>(x);
      }
    } else if (key == "preroll") {
      out.preRoll = v.cast<int>();
    } else {
      badKeyword("dynamics", key, {"frequency", "damping", "preroll"});
    }
  }
  fur::validateDynamicsParams(out.params, "dynamics");
  if (out.preRoll < -1 || out.preRoll > 10000000)
    throw py::value_error("dynamics['preroll'] " + std::to_string(out.preRoll) +
                          " is out of range [0, 10000000] frames");
  return out;
}

// ---- Model ------------------------------------------------------------------------------------

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
    } else {
      badKeyword("load", key, {"triangles", "unit_scale", "no_fur", "directions"});
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

// `preset` with every keyword set by its preset-file name (nested objects merge into the preset's).
fur::FurParams furParams(const std::string& preset, const py::kwargs& fields) {
  const fur::FurParams base = fur::loadFurPreset(preset);
  if (fields.empty()) return base;
  nlohmann::json doc = nlohmann::json::parse(fur::furPresetJson(base));
  for (const auto& [k, v] : fields) {
    const std::string key = py::str(k);
    nlohmann::json value = toJson(v);
    if (value.is_object() && doc.contains(key) && doc[key].is_object()) {
      doc[key].merge_patch(value);
    } else {
      if (key == "hairs") doc.erase("density");
      if (key == "density") doc.erase("hairs");
      doc[key] = value;
    }
  }
  return fur::parseFurPreset(doc.dump(), "fur()");
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

// ---- Hairs
// ----------------------------------------------------------------------------------------

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
  h->seconds = playback.options().startSeconds + frame / playback.options().framesPerSecond;
  return h;
}

// The playback options of a clip (or None) at `time` (a sequence's frame 0 is at `time`).
scene::PlaybackOptions playbackOptions(scene::Model& model, const py::object& clip, double time,
                                       double fps, const Dynamics& dyn) {
  scene::PlaybackOptions po;
  po.clip = clipIndex(model, clip);
  po.framesPerSecond = fps;
  po.startSeconds = time;
  po.hairSource = scene::HairSource::Cpu;
  po.dynamics = dyn.on;
  po.dynamicsParams = dyn.params;
  po.preRollFrames = dyn.preRoll;
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
    const int f = next++;
    py::gil_scoped_release release;
    playback->poseFrame(f);
    playback->evaluateFur(fur::FurView{});
    return takeHairs(*playback, fur.fur, f);
  }
};

// ---- Analysis
// -------------------------------------------------------------------------------------

// The CSV text as a dict of numpy columns named by its header.
py::dict columns(const std::string& csv) {
  std::istringstream in(csv);
  std::string header;
  std::getline(in, header);
  std::vector<std::string> names;
  std::stringstream hs(header);
  for (std::string n; std::getline(hs, n, ',');) names.push_back(n);
  std::vector<std::vector<double>> values(names.size());
  for (std::string line; std::getline(in, line);) {
    std::stringstream ls(line);
    std::size_t c = 0;
    for (std::string cell; std::getline(ls, cell, ',') && c < names.size(); ++c)
      values[c].push_back(cell == "nan" ? std::nan("") : std::stod(cell));
  }
  py::dict d;
  for (std::size_t c = 0; c < names.size(); ++c) {
    if (names[c] == "frame" || names[c] == "held") {
      std::vector<std::int64_t> ints(values[c].begin(), values[c].end());
      d[py::str(names[c])] =
          py::array_t<std::int64_t>(static_cast<py::ssize_t>(ints.size()), ints.data());
    } else {
      d[py::str(names[c])] =
          py::array_t<double>(static_cast<py::ssize_t>(values[c].size()), values[c].data());
    }
  }
  return d;
}

py::dict analyze(PyModel& m, const py::object& clip, const py::object& furArg,
                 const py::object& frames, const py::object& dynamics, double hold,
                 const std::string& groups, double fps, double time, const py::object& sweep) {
  scene::Model& model = *m.model;
  const std::shared_ptr<const scene::Fur> fur = furOf(m, furArg);
  const Dynamics dyn = dynamicsFrom(dynamics);
  scene::AnalysisOptions opt;
  opt.clip = clipIndex(model, clip);
  opt.clock.fps = fps;  // (analyzeClip checks the values)
  opt.clock.startSeconds = time;
  opt.clock.preRollFrames = dyn.preRoll;
  opt.dynamics = dyn.on;
  opt.dynamicsParams = dyn.params;
  opt.holdSeconds = hold;
  if (groups != "region" && groups != "segment")
    throw py::value_error("groups '" + groups + "' (accepted: region, segment)");
  opt.groups = groups == "segment" ? scene::AnalysisGroups::Segment : scene::AnalysisGroups::Region;
  const scene::FrameRange r = frameRange(frames, scene::wholeClip(model, opt.clip, fps));
  opt.firstFrame = r.first;
  opt.lastFrame = r.last;
  std::string csv;
  if (!sweep.is_none()) {
    const scene::SweepSpec spec = scene::parseSweep(sweep.cast<std::string>());
    py::gil_scoped_release release;
    csv = scene::sweepCsv(scene::sweepClip(model, *fur, opt, spec));
  } else {
    py::gil_scoped_release release;
    csv = scene::analysisCsv(scene::analyzeClip(model, *fur, opt));
  }
  return columns(csv);
}

// ---- Export
// ---------------------------------------------------------------------------------------

std::vector<std::string> exportFrames(PyModel& m, const py::object& clip, const py::object& furArg,
                                      const py::object& frames, const std::string& format,
                                      const std::string& out, double fps, double time,
                                      const py::object& dynamics, bool resume) {
  scene::Model& model = *m.model;
  const std::shared_ptr<const scene::Fur> fur = furOf(m, furArg);
  scene::ExportOptions eo;
  eo.format = scene::parseExportFormat(format);
  eo.out = out;
  eo.resume = resume;
  const Dynamics dyn = dynamicsFrom(dynamics);
  eo.playback = playbackOptions(model, clip, time, fps, dyn);
  eo.frames = frameRange(frames, scene::wholeClip(model, eo.playback.clip, fps));
  scene::ExportReport r;
  {
    py::gil_scoped_release release;
    r = scene::exportClip(model, *fur, eo);
  }
  return r.files;
}

// ---- Render
// ---------------------------------------------------------------------------------------

#ifdef PELAGE_HAVE_RENDER
py::array_t<std::uint8_t> render(PyModel& m, const py::object& clip, const py::object& furArg,
                                 int frame, double fps, double time, std::pair<int, int> size,
                                 const std::string& camera, double fov, bool follow,
                                 const std::string& hairSource, const std::string& shading,
                                 bool lines, bool transparency, bool shadows, bool selfShadowing,
                                 int samples, const py::object& dynamics,
                                 const py::object& skinColor) {
  scene::Model& model = *m.model;
  const std::shared_ptr<const scene::Fur> fur = furOf(m, furArg);
  viewer::SequenceOptions o;
  const Dynamics dyn = dynamicsFrom(dynamics);
  o.playback = playbackOptions(model, clip, time, fps, dyn);
  o.playback.hairSource = scene::parseHairSource(hairSource);
  o.frames = {frame, frame};
  o.width = size.first;
  o.height = size.second;
  o.samples = samples;
  o.camera.preset = scene::parseCameraPreset(camera);
  o.camera.fovYDegrees = static_cast<float>(fov);
  o.camera.track = follow;
  o.look.hairShading = scene::parseHairShading(shading);
  o.look.hairWidth = lines ? scene::HairWidth::Lines : scene::HairWidth::Strands;
  o.look.transparency = transparency;
  o.shadows = shadows;
  o.selfShadowing = selfShadowing;
  if (!skinColor.is_none()) {
    const auto c = skinColor.cast<std::vector<float>>();
    if (c.size() != 3 ||
        std::any_of(c.begin(), c.end(), [](float v) { return !(v >= 0.f && v <= 1.f); }))
      throw py::value_error("skin_color: three values in [0, 1] (r, g, b)");
    o.skinColor = Eigen::Vector3f(c[0], c[1], c[2]);
  }
  o.outDir = ".";  // (nothing is written)
  viewer::validateSequenceOptions(o);
  viewer::Image image;
  {
    py::gil_scoped_release release;
    auto context = viewer::createHeadlessContext();
    viewer::SequenceRenderer renderer(model, *fur, o);
    renderer.render(frame, image);
  }
  py::array_t<std::uint8_t> rgb({static_cast<py::ssize_t>(image.height),
                                 static_cast<py::ssize_t>(image.width), py::ssize_t{3}});
  auto out = rgb.mutable_unchecked<3>();
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      const std::uint8_t* p = image.pixel(x, y);
      for (int c = 0; c < 3; ++c) out(y, x, c) = p[c];
    }
  return rgb;
}
#endif

}  // namespace
}  // namespace pelage::python

PYBIND11_MODULE(_pelage, m) {
  using namespace pelage;
  using namespace pelage::python;
  m.doc() = "pelage: animated furred creatures (Van Gelder & Wilhelms 1997 fur model)";

  static py::exception<InputError> inputError(m, "InputError", PyExc_ValueError);
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const MissingFileError& e) {
      PyErr_SetString(PyExc_FileNotFoundError, e.what());
    } catch (const InputError& e) {
      PyErr_SetString(inputError.ptr(), pythonMessage(e).c_str());
    }
  });

  m.def(
      "set_threads",
      [](int n) {
        if (n < 0 || n > 1024)
          throw py::value_error("threads " + std::to_string(n) + " is out of range [0, 1024]");
        setThreadCount(n);
      },
      py::arg("n"), "Worker threads for pelage's computations (0: all cores).");
  m.def(
      "threads", [] { return threadCount(); }, "The worker thread count in use.");

  py::class_<PyModel>(m, "Model", "A creature: body, skin and clips (constant).")
      .def_property_readonly("name", [](const PyModel& s) { return s.model->name; })
      .def_property_readonly("source", [](const PyModel& s) { return s.model->source; })
      .def_property_readonly(
          "segments",
          [](const PyModel& s) {
            std::vector<std::string> names;
            for (const auto& seg : s.model->body.segments) names.push_back(seg.name);
            return names;
          },
          "The body's segments, parents before children.")
      .def_property_readonly("regions", [](const PyModel& s) { return s.model->skin.regionNames; })
      .def_property_readonly(
          "clips",
          [](const PyModel& s) {
            py::dict d;
            for (const auto& c : s.model->clips) d[py::str(c.name)] = shortestDouble(c.duration);
            return d;
          },
          "Clip name -> duration in seconds.")
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
            const auto nV = static_cast<py::ssize_t>(pos.size() / 3);
            const auto& tri = s.model->skin.triangles;
            return py::make_tuple(
                py::array_t<float>({nV, py::ssize_t{3}}, pos.data()),
                py::array_t<float>({nV, py::ssize_t{3}}, nrm.data()),
                py::array_t<std::int32_t>(
                    {static_cast<py::ssize_t>(tri.size() / 3), py::ssize_t{3}}, tri.data()));
          },
          py::arg("clip") = py::none(), py::arg("time") = 0.0,
          "The posed skin: (positions (nV, 3), normals (nV, 3), triangles (nT, 3)), metres, Z up.")
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
            return f;
          },
          py::arg("preset") = "default",
          "Fur from a preset with any preset field set by keyword (hairs=..., overcoat={...}).")
      .def("__repr__", [](const PyModel& s) {
        return "<pelage.Model " + s.model->name + ": " + std::to_string(s.model->body.size()) +
               " segments, " + std::to_string(s.model->skin.numTriangles()) + " triangles, " +
               std::to_string(s.model->clips.size()) + " clips>";
      });

  py::class_<PyFur>(m, "Fur", "A creature's fur: parameters and grown roots (constant).")
      .def_property_readonly(
          "params",
          [](const PyFur& f) {
            return fromJson(nlohmann::json::parse(fur::furPresetJson(f.fur->params)));
          },
          "The parameters, as the preset file's fields.")
      .def_property_readonly(
          "roots", [](const PyFur& f) { return f.fur->roots.total(); }, "Hairs grown (both coats).")
      .def("hairs", &hairsOf, py::arg("clip") = py::none(), py::arg("time") = 0.0,
           py::arg("dynamics") = py::none(), py::arg("fps") = 30.0,
           "One frame's hairs (every hair, no culling): the clip at `time` (None: the rest "
           "pose); with dynamics, the clip's frames from its start up to `time` at `fps`.")
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
          py::arg("dynamics") = py::none(), py::arg("time") = 0.0,
          "Iterates the frames of a clip in order (frame f at clip time time + f / fps), the "
          "dynamic springs stepping from one frame to the next.");

  py::class_<FrameIterator, std::shared_ptr<FrameIterator>>(m, "FrameIterator")
      .def("__iter__", [](std::shared_ptr<FrameIterator> self) { return self; })
      .def("__next__", &FrameIterator::step);

  py::class_<PyHairs, std::shared_ptr<PyHairs>>(
      m, "Hairs",
      "One frame's hairs; every array is a view of pelage's buffers and keeps them alive.")
      .def("__len__", &PyHairs::count)
      .def_property_readonly("frame", [](const PyHairs& h) { return h.frameNumber; })
      .def_property_readonly("time", [](const PyHairs& h) { return h.seconds; })
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
      .def_property_readonly("styles", [](const PyHairs& h) {
        return py::make_tuple(fur::styleName(h.frame.coats[0].layout.style),
                              fur::styleName(h.frame.coats[1].layout.style));
      });

  m.def("load", &load, py::arg("model") = "monkey",
        "Loads a creature: 'monkey' (built-in), a creature .json, a .gltf/.glb, or a mesh; "
        "keywords triangles, unit_scale, no_fur, directions as the command line's options.");
  m.def("analyze", &analyze, py::arg("model"), py::arg("clip") = py::none(),
        py::arg("fur") = py::none(), py::kw_only(), py::arg("frames") = py::none(),
        py::arg("dynamics") = py::none(), py::arg("hold") = 0.0, py::arg("groups") = "region",
        py::arg("fps") = 30.0, py::arg("time") = 0.0, py::arg("sweep") = py::none(),
        "`pelage analyze` in Python: a dict of numpy columns named as the CSV's.");
  m.def("export", &exportFrames, py::arg("model"), py::arg("clip") = py::none(),
        py::arg("fur") = py::none(), py::kw_only(), py::arg("frames") = py::none(),
        py::arg("format") = "ply", py::arg("out"), py::arg("fps") = 30.0, py::arg("time") = 0.0,
        py::arg("dynamics") = py::none(), py::arg("resume") = false,
        "`pelage export` in Python: writes the files and returns their paths.");
#ifdef PELAGE_HAVE_RENDER
  m.def("render", &render, py::arg("model"), py::arg("clip") = py::none(),
        py::arg("fur") = py::none(), py::kw_only(), py::arg("frame") = 0, py::arg("fps") = 30.0,
        py::arg("time") = 0.0, py::arg("size") = std::pair<int, int>(1280, 720),
        py::arg("camera") = "three-quarter", py::arg("fov") = 35.0, py::arg("follow") = false,
        py::arg("hair_source") = "gpu", py::arg("shading") = "paper", py::arg("lines") = false,
        py::arg("transparency") = true, py::arg("shadows") = false,
        py::arg("self_shadowing") = true, py::arg("samples") = -1, py::arg("dynamics") = py::none(),
        py::arg("skin_color") = py::none(),
        "`pelage render` of one frame in Python (EGL, no display): an (H, W, 3) uint8 image.");
#endif
}
