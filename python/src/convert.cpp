// The Python package's conversions (convert.h).
#include "convert.h"

#include <cmath>
#include <cstdint>
#include <mutex>
#include <optional>

#include "pelage/fur/fur_params.h"
#include "pelage/scene/playback.h"
#include "pelage/util/json_reader.h"

namespace pelage::python {

// ---- Errors -------------------------------------------------------------------------------------

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

// ---- Warnings and interrupts -------------------------------------------------------------------

namespace {
std::mutex gWarningMutex;
std::vector<std::string> gWarnings;
}  // namespace

void queueWarning(const std::string& message) {
  std::lock_guard<std::mutex> lock(gWarningMutex);
  gWarnings.push_back(message);
}

void flushWarnings() {
  std::vector<std::string> pending;
  {
    std::lock_guard<std::mutex> lock(gWarningMutex);
    pending.swap(gWarnings);
  }
  for (const std::string& w : pending)
    if (PyErr_WarnEx(PyExc_UserWarning, ("pelage: " + w).c_str(), 1) != 0)
      throw py::error_already_set();
}

void pollPython() {
  py::gil_scoped_acquire gil;
  if (PyErr_CheckSignals() != 0) throw py::error_already_set();
  flushWarnings();
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

double shortestDouble(double d) {
  const auto f = static_cast<float>(d);
  if (!std::isfinite(d) || static_cast<double>(f) != d) return d;
  return shortestDecimal(f);
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

scene::FrameRange frameRange(const py::object& frames, const scene::FrameRange& fallback) {
  if (frames.is_none()) return fallback;
  scene::FrameRange r;
  const auto integer = [](const py::handle& v) {
    if (!py::isinstance<py::int_>(v) || py::isinstance<py::bool_>(v))
      throw py::type_error("frames: frame numbers are ints, got " +
                           py::str(py::type::of(v).attr("__name__")).cast<std::string>());
    const long long x = v.cast<long long>();
    return static_cast<int>(std::clamp<long long>(x, -1, scene::kMaxFrameNumber + 1LL));
  };
  if (py::isinstance<py::int_>(frames)) {
    r.first = r.last = integer(frames);
  } else if (py::isinstance(frames, py::module_::import("builtins").attr("range"))) {
    const int start = integer(frames.attr("start")), stop = integer(frames.attr("stop")),
              step = integer(frames.attr("step"));
    if (step < 1 || stop <= start)
      throw py::value_error("frames: " + py::repr(frames).cast<std::string>() +
                            " has no frames (a range with a positive step and stop > start)");
    r.first = start;
    r.step = step;
    r.last = start + (stop - 1 - start) / step * step;
  } else if (py::isinstance<py::sequence>(frames) && !py::isinstance<py::str>(frames) &&
             py::len(frames) == 2) {
    const py::sequence pair = frames.cast<py::sequence>();
    r.first = integer(pair[0]);
    r.last = integer(pair[1]);
  } else {
    throw py::value_error("frames: an int, a (first, last) pair or a range");
  }
  scene::validateFrameRange(r);  // the one frame-range rule (and its message)
  return r;
}

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
  scene::validatePreRoll(out.preRoll, "dynamics['preroll']");
  return out;
}

fur::VertexGroom vertexGroomFrom(int vertices, const py::object& length, const py::object& density,
                                 const py::object& tint, const py::object& comb,
                                 const py::object& clump, const py::object& stiffness,
                                 const py::object& segmentDirectionWeight,
                                 const py::object& curlRadius, const py::object& curlTurns,
                                 const py::object& widthScale,
                                 const py::object& colorSourceWeight) {
  const auto nV = static_cast<py::ssize_t>(vertices);
  const auto column = [&](const py::object& o, const char* name) {
    std::vector<float> out;
    if (o.is_none()) return out;
    const auto a = py::array_t<float, py::array::c_style | py::array::forcecast>::ensure(o);
    if (!a || a.ndim() != 1 || a.shape(0) != nV)
      throw InputError(std::string(name),
                       str("must be an array of shape (", nV, ",), one value per skin vertex"));
    out.assign(a.data(), a.data() + nV);
    return out;
  };
  // Rows of `width` values (shape (nV, width)).
  const auto rows = [&](const py::object& o, const char* name, py::ssize_t width,
                        const char* what) {
    using Array = py::array_t<float, py::array::c_style | py::array::forcecast>;
    if (o.is_none()) return std::optional<Array>();
    const auto a = Array::ensure(o);
    if (!a || a.ndim() != 2 || a.shape(0) != nV || a.shape(1) != width)
      throw InputError(std::string(name), str("must be an array of shape (", nV, ", ", width,
                                              "), one ", what, " per skin vertex"));
    return std::optional<Array>(a);
  };
  const auto triples = [&](const py::object& o, const char* name, const char* what) {
    std::vector<Eigen::Vector3f> out;
    const auto a = rows(o, name, 3, what);
    if (!a) return out;
    for (py::ssize_t v = 0; v < nV; ++v) out.emplace_back(a->at(v, 0), a->at(v, 1), a->at(v, 2));
    return out;
  };
  fur::VertexGroom g;
  g.length = column(length, "length");
  g.density = column(density, "density");
  g.tint = triples(tint, "tint", "RGB");
  g.comb = triples(comb, "comb", "direction times amount");
  g.clump = column(clump, "clump");
  const auto pairs = [&](const py::object& o, const char* name, const char* what) {
    std::vector<Eigen::Vector2f> out;
    if (const auto a = rows(o, name, 2, what))
      for (py::ssize_t v = 0; v < nV; ++v) out.emplace_back(a->at(v, 0), a->at(v, 1));
    return out;
  };
  g.stiffness = pairs(stiffness, "stiffness", "(overcoat, undercoat) stiffness");
  g.segmentDirectionWeight = pairs(segmentDirectionWeight, "segment_direction_weight",
                                   "(overcoat, undercoat) segment direction weight");
  g.curlRadius = pairs(curlRadius, "curl_radius", "(overcoat, undercoat) curl radius");
  g.curlTurns = pairs(curlTurns, "curl_turns", "(overcoat, undercoat) curl turns");
  g.widthScale = pairs(widthScale, "width_scale", "(overcoat, undercoat) width scale");
  if (!colorSourceWeight.is_none()) {
    if (!py::isinstance<py::dict>(colorSourceWeight))
      throw InputError("color_source_weight", "must be a dict of the five colour sources (" +
                                                  fur::colorSourceNames() +
                                                  ") to arrays of shape (vertices, 2)");
    const auto d = colorSourceWeight.cast<py::dict>();
    for (const auto& item : d) {
      const std::string key = py::str(item.first);
      if (!fur::findColorSource(key))
        throw InputError("color_source_weight",
                         str("has '", key, "'; accepted: ", fur::colorSourceNames()));
    }
    for (int s = 0; s < fur::kColorSourceCount; ++s) {
      const std::string name(fur::colorSourceName(static_cast<fur::ColorSource>(s)));
      if (!d.contains(name))
        throw InputError("color_source_weight",
                         "lacks '" + name + "': give the weights of all five colour sources");
      g.colorSourceWeight[static_cast<std::size_t>(s)] =
          pairs(d[name.c_str()], ("color_source_weight['" + name + "']").c_str(),
                "(overcoat, undercoat) weight");
    }
  }
  return g;
}

py::dict groomDict(const fur::VertexGroom& g) {
  py::dict d;
  if (!g.length.empty())
    d["length"] = py::array_t<float>({static_cast<py::ssize_t>(g.length.size())}, g.length.data());
  if (!g.density.empty())
    d["density"] =
        py::array_t<float>({static_cast<py::ssize_t>(g.density.size())}, g.density.data());
  const auto triples = [](const std::vector<Eigen::Vector3f>& v) {
    return py::array_t<float>({static_cast<py::ssize_t>(v.size()), py::ssize_t{3}},
                              v.data()->data());
  };
  if (!g.tint.empty()) d["tint"] = triples(g.tint);
  if (!g.comb.empty()) d["comb"] = triples(g.comb);
  if (!g.clump.empty())
    d["clump"] = py::array_t<float>({static_cast<py::ssize_t>(g.clump.size())}, g.clump.data());
  const auto pairs = [](const std::vector<Eigen::Vector2f>& v) {
    return py::array_t<float>({static_cast<py::ssize_t>(v.size()), py::ssize_t{2}},
                              v.data()->data());
  };
  if (!g.stiffness.empty()) d["stiffness"] = pairs(g.stiffness);
  if (!g.segmentDirectionWeight.empty())
    d["segment_direction_weight"] = pairs(g.segmentDirectionWeight);
  if (!g.curlRadius.empty()) d["curl_radius"] = pairs(g.curlRadius);
  if (!g.curlTurns.empty()) d["curl_turns"] = pairs(g.curlTurns);
  if (!g.widthScale.empty()) d["width_scale"] = pairs(g.widthScale);
  if (g.hasColorSourceWeights()) {
    py::dict w;
    for (int s = 0; s < fur::kColorSourceCount; ++s)
      w[py::str(std::string(fur::colorSourceName(static_cast<fur::ColorSource>(s))))] =
          pairs(g.colorSourceWeight[static_cast<std::size_t>(s)]);
    d["color_source_weight"] = w;
  }
  return d;
}

py::dict columns(const scene::AnalysisTable& t) {
  py::dict d;
  for (std::size_t c = 0; c < t.names.size(); ++c) {
    const std::vector<double>& v = t.columns[c];
    if (t.names[c] == "frame" || t.names[c] == "held") {
      py::array_t<std::int64_t> a(static_cast<py::ssize_t>(v.size()));
      auto w = a.mutable_unchecked<1>();
      for (std::size_t i = 0; i < v.size(); ++i)
        w(static_cast<py::ssize_t>(i)) = static_cast<std::int64_t>(std::llround(v[i]));
      d[py::str(t.names[c])] = a;
    } else {
      d[py::str(t.names[c])] = py::array_t<double>(static_cast<py::ssize_t>(v.size()), v.data());
    }
  }
  return d;
}

scene::SweepSpec sweepOf(const py::object& sweep) {
  if (py::isinstance<py::str>(sweep)) return scene::parseSweep(sweep.cast<std::string>());
  if (!py::isinstance<py::dict>(sweep) || py::len(sweep) != 1)
    throw py::value_error(
        "sweep: 'NAME=A:B:N', {NAME: [values]} or {NAME: (first, last, count)} with NAME "
        "stiffness, frequency or damping (one parameter)");
  const auto item = *sweep.cast<py::dict>().begin();
  const std::string name = py::str(item.first);
  const py::handle v = item.second;
  const auto number = [&](const py::handle& x) {
    if (!py::isinstance<py::int_>(x) && !py::isinstance<py::float_>(x) && !py::hasattr(x, "dtype"))
      throw py::value_error("sweep['" + name + "']: values are numbers, got " +
                            py::str(py::type::of(x).attr("__name__")).cast<std::string>());
    return x.cast<double>();
  };
  if (py::isinstance<py::tuple>(v)) {
    const py::tuple t = v.cast<py::tuple>();
    if (t.size() != 3 || !py::isinstance<py::int_>(t[2]))
      throw py::value_error("sweep['" + name +
                            "']: a tuple is a range (first, last, count); give a list for values");
    return scene::sweepRange(name, number(t[0]), number(t[1]), t[2].cast<int>());
  }
  if (!py::isinstance<py::sequence>(v) && !py::hasattr(v, "tolist"))
    throw py::value_error("sweep['" + name + "']: a list of values or (first, last, count)");
  const py::sequence seq =
      py::hasattr(v, "tolist") ? v.attr("tolist")().cast<py::sequence>() : v.cast<py::sequence>();
  std::vector<double> values;
  for (const py::handle x : seq) values.push_back(number(x));
  return scene::sweepValues(name, std::move(values));
}

}  // namespace pelage::python
