// The Python package's conversions between Python objects and pelage's values, in one place:
// errors in Python's words, keyword arguments, warnings and Ctrl-C, JSON-like values (fur
// parameters), frame ranges, dynamics, sweeps and analysis tables. module.cpp defines the API on
// top of them.
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>  // in every file: the same casters for std types everywhere

#include <algorithm>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "pelage/fur/dynamics.h"
#include "pelage/fur/groom.h"
#include "pelage/scene/analyze.h"
#include "pelage/scene/frame_range.h"
#include "pelage/util/error.h"

namespace pelage::python {

namespace py = pybind11;

// A library error in Python's words: a field ("hair source") becomes the keyword (hair_source).
std::string pythonMessage(const InputError& e);

// ValueError: `function` has no keyword `key`; lists the accepted ones.
[[noreturn]] void badKeyword(const std::string& function, const std::string& key,
                             const std::vector<std::string>& accepted);

// A function's keyword arguments, checked against the ones it accepts (an unknown one is a
// ValueError listing them, as fur() does), read with their defaults.
class Keywords {
 public:
  Keywords(std::string function, const py::kwargs& kwargs, std::vector<std::string> accepted)
      : function_(std::move(function)), kwargs_(kwargs) {
    for (const auto& item : kwargs) {
      const std::string key = py::str(item.first);
      if (std::find(accepted.begin(), accepted.end(), key) == accepted.end())
        badKeyword(function_, key, accepted);
    }
  }
  // The keyword's value, or None.
  py::object object(const char* name) const {
    return kwargs_.contains(name) ? py::reinterpret_borrow<py::object>(kwargs_[name]) : py::none();
  }
  // The keyword's value as T, or `fallback`; TypeError naming it for a value of another type.
  template <typename T>
  T get(const char* name, T fallback) const {
    if (!kwargs_.contains(name)) return fallback;
    const py::handle v = kwargs_[name];
    try {
      return v.cast<T>();
    } catch (const py::cast_error&) {
      throw py::type_error(function_ + "(): " + name + " cannot be a " +
                           py::str(py::type::of(v).attr("__name__")).cast<std::string>());
    }
  }

 private:
  std::string function_;
  const py::kwargs& kwargs_;
};

// pelage's warnings, queued by whichever thread warns (no GIL needed; util/log.h's sink), raised as
// Python UserWarnings by flushWarnings() on the calling thread: after each call, and each frame.
void queueWarning(const std::string& message);
// Raises the queued warnings through Python's `warnings` (needs the GIL); an exception a filter
// turns a warning into propagates.
void flushWarnings();
// checkInterrupt()'s poll (util/interrupt.h), once a frame: Python's pending signals (Ctrl-C raises
// KeyboardInterrupt through the running call, whose unwinding removes what it half-wrote), and the
// queued warnings.
void pollPython();

// A Python value (None, bool, int, float, str, dict, sequence, numpy array) as JSON (fur
// parameters are their preset file's fields); ValueError for anything else.
nlohmann::json toJson(const py::handle& value);
// A float32 value as the double Python prints as the float's shortest decimal (0.3f -> 0.3, not
// 0.30000001192092896); other doubles unchanged.
double shortestDouble(double d);
// JSON as Python values (floats through shortestDouble).
py::object fromJson(const nlohmann::json& j);

// The frames of `frames`: None (the default of `fallback`), an int, a (first, last) pair (both
// included), or a range (any positive step; its stop excluded, as Python's).
scene::FrameRange frameRange(const py::object& frames, const scene::FrameRange& fallback);

// Dynamic fur from `dynamics`: None or False (off), True (the defaults), or a dict with
// "frequency" and "damping" (one value or one per coat) and "preroll".
struct Dynamics {
  bool on = false;
  fur::DynamicsParams params;
  int preRoll = -1;
};
Dynamics dynamicsFrom(const py::object& d);

// numpy arrays (None: absent) as a vertex groom of `vertices` vertices: length, density and clump
// of shape (vertices,), tint and comb (vertices, 3), stiffness, segment direction weight, curl
// radius and turns, width scale (vertices, 2), and colour source weights (a dict of the five
// source names to (vertices, 2)); InputError naming the keyword for another shape.
fur::VertexGroom vertexGroomFrom(int vertices, const py::object& length, const py::object& density,
                                 const py::object& tint, const py::object& comb,
                                 const py::object& clump, const py::object& stiffness,
                                 const py::object& segmentDirectionWeight,
                                 const py::object& curlRadius, const py::object& curlTurns,
                                 const py::object& widthScale, const py::object& colorSourceWeight);
// A vertex groom as a dict of numpy arrays, copied ("length", "density", "tint", "comb"; absent
// ones left out).
py::dict groomDict(const fur::VertexGroom& g);

// A table as a dict of numpy columns in its order: "frame" and "held" int64, the rest float64, the
// library's values as computed (no text round trip).
py::dict columns(const scene::AnalysisTable& t);

// A sweep: "NAME=A:B:N" as the command line's, {"NAME": [v, ...]} (the values) or
// {"NAME": (first, last, count)} (count values evenly from first to last).
scene::SweepSpec sweepOf(const py::object& sweep);

}  // namespace pelage::python
