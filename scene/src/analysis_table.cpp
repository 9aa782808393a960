// Analysis results as tables (named columns, one value per frame) and CSV text: the one owner of
// the column names (analysisTable, sweepTable), their CSV (tableCsv) and the joining of a split
// sweep's parts (mergeSweepCsv).
#include <charconv>
#include <cmath>
#include <cstdio>
#include <map>

#include "pelage/scene/analyze.h"
#include "pelage/util/error.h"

namespace pelage::scene {
namespace {

// A value as the shortest decimal that reads back as the same double.
std::string number(double v) {
  if (std::isnan(v)) return "nan";
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
}

std::string columnName(const std::string& name) {
  std::string s = name;
  for (char& ch : s)
    if (ch == ',' || ch == '"' || ch == '\n' || ch == '\r' || ch == ']' || ch == '[') ch = '_';
  return s;
}

// Appends a column named `name` whose row i is value(frames[i]).
template <typename F>
void addColumn(AnalysisTable& t, const std::string& name, const std::vector<FrameAnalysis>& frames,
               F value) {
  t.names.push_back(name);
  std::vector<double>& c = t.columns.emplace_back();
  c.reserve(frames.size());
  for (const FrameAnalysis& f : frames) c.push_back(value(f));
}

// The end-point columns of one model (quasi-static or dynamic), prefixed `p`.
void addEndColumns(AnalysisTable& t, const std::string& p, const std::vector<std::string>& groups,
                   const std::vector<FrameAnalysis>& frames, EndStats FrameAnalysis::*end) {
  const std::pair<const char*, double EndStats::*> scalars[] = {
      {"gravity_angle_deg", &EndStats::gravityAngleDeg},
      {"tip_height_mm", &EndStats::tipHeightMm},
      {"droop_body_up_mm", &EndStats::droopBodyUpMm},
      {"tip_speed_m_per_s", &EndStats::tipSpeed}};
  addColumn(t, p + "droop_mean_deg", frames,
            [&](const FrameAnalysis& f) { return (f.*end).all.droopMeanDeg; });
  addColumn(t, p + "droop_std_deg", frames,
            [&](const FrameAnalysis& f) { return (f.*end).all.droopStdDeg; });
  for (const auto& [name, member] : scalars)
    addColumn(t, p + name, frames, [&](const FrameAnalysis& f) { return (f.*end).*member; });
  for (std::size_t g = 0; g < groups.size(); ++g)
    addColumn(t, p + "droop_mean_deg[" + columnName(groups[g]) + "]", frames,
              [&](const FrameAnalysis& f) { return (f.*end).groups[g].droopMeanDeg; });
  for (std::size_t g = 0; g < groups.size(); ++g)
    addColumn(t, p + "droop_std_deg[" + columnName(groups[g]) + "]", frames,
              [&](const FrameAnalysis& f) { return (f.*end).groups[g].droopStdDeg; });
}

// The columns every table starts with: frame, time_s, held.
void addFrameColumns(AnalysisTable& t, const std::vector<FrameAnalysis>& frames) {
  addColumn(t, "frame", frames, [](const FrameAnalysis& f) { return double(f.frame); });
  addColumn(t, "time_s", frames, [](const FrameAnalysis& f) { return f.seconds; });
  addColumn(t, "held", frames, [](const FrameAnalysis& f) { return f.held ? 1.0 : 0.0; });
}

}  // namespace

AnalysisTable analysisTable(const AnalysisResult& r) {
  AnalysisTable t;
  const std::vector<FrameAnalysis>& frames = r.frames;
  addFrameColumns(t, frames);
  addColumn(t, "body_up_x", frames, [](const FrameAnalysis& f) { return f.bodyUp.x(); });
  addColumn(t, "body_up_y", frames, [](const FrameAnalysis& f) { return f.bodyUp.y(); });
  addColumn(t, "body_up_z", frames, [](const FrameAnalysis& f) { return f.bodyUp.z(); });
  addColumn(t, "pitch_deg", frames, [](const FrameAnalysis& f) { return f.pitchDeg; });
  addColumn(t, "roll_deg", frames, [](const FrameAnalysis& f) { return f.rollDeg; });
  addColumn(t, "tilt_deg", frames, [](const FrameAnalysis& f) { return f.tiltDeg; });
  addEndColumns(t, "qs_", r.groupNames, frames, &FrameAnalysis::quasiStatic);
  if (r.dynamics) {
    addEndColumns(t, "dyn_", r.groupNames, frames, &FrameAnalysis::dynamic);
    addColumn(t, "lag_deg", frames, [](const FrameAnalysis& f) { return f.lagDeg; });
    addColumn(t, "dyn_offset_mm", frames, [](const FrameAnalysis& f) { return f.offsetMm; });
    addColumn(t, "dyn_stop_response_mm", frames,
              [](const FrameAnalysis& f) { return f.stopResponseMm; });
  }
  return t;
}

std::string tableCsv(const AnalysisTable& t) {
  PELAGE_CHECK(t.names.size() == t.columns.size(), "table of ", t.names.size(), " names, ",
               t.columns.size(), " columns");
  std::string out;
  for (std::size_t c = 0; c < t.names.size(); ++c) out += (c ? "," : "") + t.names[c];
  out += "\n";
  for (std::size_t row = 0; row < t.rows(); ++row) {
    for (std::size_t c = 0; c < t.columns.size(); ++c) {
      const double v = t.columns[c][row];
      const bool integer = t.names[c] == "frame" || t.names[c] == "held";
      out += (c ? "," : "") + (integer ? std::to_string(std::llround(v)) : number(v));
    }
    out += "\n";
  }
  return out;
}

std::string analysisCsv(const AnalysisResult& r) {
  return tableCsv(analysisTable(r));
}

AnalysisTable sweepTable(const SweepResult& sweep) {
  PELAGE_CHECK(!sweep.runs.empty() && sweep.runs.size() == sweep.values.size(), "sweep of ",
               sweep.runs.size(), " runs");
  const std::vector<FrameAnalysis>& frames = sweep.runs.front().frames;
  AnalysisTable t;
  addFrameColumns(t, frames);
  addColumn(t, "pitch_deg", frames, [](const FrameAnalysis& f) { return f.pitchDeg; });
  addColumn(t, "tilt_deg", frames, [](const FrameAnalysis& f) { return f.tiltDeg; });
  const std::string prefix = sweep.runs.front().dynamics ? "dyn_" : "qs_";
  const auto end =
      sweep.runs.front().dynamics ? &FrameAnalysis::dynamic : &FrameAnalysis::quasiStatic;
  const std::pair<const char*, bool> blocks[] = {{"droop_mean_deg", true},
                                                 {"tip_height_mm", false}};
  for (const auto& [column, droop] : blocks)
    for (std::size_t v = 0; v < sweep.values.size(); ++v) {
      const std::vector<FrameAnalysis>& run = sweep.runs[v].frames;
      PELAGE_CHECK(run.size() == frames.size(), "sweep runs of different lengths");
      t.names.push_back(prefix + column + "[" + sweep.spec.parameter + "=" + str(sweep.values[v]) +
                        "]");
      std::vector<double>& c = t.columns.emplace_back();
      for (const FrameAnalysis& f : run)
        c.push_back(droop ? (f.*end).all.droopMeanDeg : (f.*end).tipHeightMm);
    }
  return t;
}

std::string sweepCsv(const SweepResult& sweep) {
  return tableCsv(sweepTable(sweep));
}

namespace {

// A sweep CSV's first value column: "qs_droop_mean_deg[NAME=V]" or "dyn_droop_mean_deg[NAME=V]".
bool isSweepDroopColumn(const std::string& h) {
  return h.rfind("qs_droop_mean_deg[", 0) == 0 || h.rfind("dyn_droop_mean_deg[", 0) == 0;
}

// The swept parameter of a value column's name ("stiffness" of "qs_droop_mean_deg[stiffness=0.2]").
std::string sweptName(const std::string& h) {
  const std::size_t open = h.find('[');
  return h.substr(open + 1, h.find('=', open) - open - 1);
}

std::vector<std::string> splitLine(const std::string& line) {
  std::vector<std::string> cells;
  std::size_t start = 0;
  for (;;) {
    const std::size_t comma = line.find(',', start);
    cells.push_back(
        line.substr(start, comma == std::string::npos ? std::string::npos : comma - start));
    if (comma == std::string::npos) return cells;
    start = comma + 1;
  }
}

}  // namespace

std::string mergeSweepCsv(const std::vector<std::string>& texts,
                          const std::vector<std::string>& sources) {
  PELAGE_CHECK(texts.size() == sources.size());
  if (texts.empty()) inputError("no sweep CSV to merge");
  constexpr std::size_t kShared = 5;  // frame, time_s, held, pitch_deg, tilt_deg
  const std::vector<std::string> shared = {"frame", "time_s", "held", "pitch_deg", "tilt_deg"};
  struct Part {
    std::vector<std::vector<std::string>> rows;  // header first
    std::size_t values = 0;
  };
  std::vector<Part> parts;
  for (std::size_t i = 0; i < texts.size(); ++i) {
    Part p;
    std::size_t start = 0;
    while (start < texts[i].size()) {
      std::size_t end = texts[i].find('\n', start);
      if (end == std::string::npos) end = texts[i].size();
      p.rows.push_back(splitLine(texts[i].substr(start, end - start)));
      start = end + 1;
    }
    if (p.rows.size() < 2)
      inputError(sources[i], ": not a sweep CSV (a header and at least one row are needed)");
    const std::vector<std::string>& h = p.rows.front();
    const std::size_t columns = h.size();
    if (columns < kShared + 2 || (columns - kShared) % 2 != 0 ||
        !std::equal(shared.begin(), shared.end(), h.begin()) || !isSweepDroopColumn(h[kShared]))
      inputError(
          sources[i],
          ": not a sweep CSV (a sweep table's: frame, time_s, held, pitch_deg, tilt_deg, then "
          "qs_ or dyn_ droop and tip-height columns per value; its header is '",
          texts[i].substr(0, texts[i].find('\n')), "')");
    p.values = (columns - kShared) / 2;
    for (std::size_t r = 1; r < p.rows.size(); ++r)
      if (p.rows[r].size() != columns)
        inputError(sources[i], ": row ", r + 1, " has ", p.rows[r].size(), " cells, the header ",
                   columns);
    if (i > 0) {
      const Part& first = parts.front();
      if (p.rows.size() != first.rows.size())
        inputError(sources[i], ": ", p.rows.size() - 1, " frames, ", sources[0], " has ",
                   first.rows.size() - 1, " (parts of one sweep cover the same frames)");
      for (std::size_t r = 1; r < p.rows.size(); ++r)
        if (!std::equal(first.rows[r].begin(), first.rows[r].begin() + kShared, p.rows[r].begin()))
          inputError(sources[i], ": row ", r + 1, " (frame ", p.rows[r][0], ") differs from ",
                     sources[0],
                     " in frame, time or body orientation: not the same clip and frames");
      const std::string parameter = sweptName(h[kShared]);
      const std::string firstParameter = sweptName(first.rows[0][kShared]);
      if (h[kShared].substr(0, h[kShared].find('[')) !=
          first.rows[0][kShared].substr(0, first.rows[0][kShared].find('[')))
        inputError(sources[i], ": ", h[kShared].substr(0, h[kShared].find('[')), ", ", sources[0],
                   " has ", first.rows[0][kShared].substr(0, first.rows[0][kShared].find('[')),
                   " (parts of one sweep use the same fur model: dynamic or not)");
      if (parameter != firstParameter)
        inputError(sources[i], ": sweeps ", parameter, ", ", sources[0], " sweeps ",
                   firstParameter);
    }
    parts.push_back(std::move(p));
  }
  // Each value once.
  std::map<std::string, std::size_t> seen;
  for (std::size_t i = 0; i < parts.size(); ++i)
    for (std::size_t v = 0; v < parts[i].values; ++v) {
      const std::string& column = parts[i].rows[0][kShared + v];
      const auto [it, fresh] = seen.emplace(column, i);
      if (!fresh)
        inputError(sources[i], ": ", column, " is also in ", sources[it->second],
                   " (each value of the sweep in one part)");
    }
  std::string out;
  for (std::size_t r = 0; r < parts.front().rows.size(); ++r) {
    std::string row;
    for (std::size_t c = 0; c < kShared; ++c) row += (c ? "," : "") + parts.front().rows[r][c];
    for (int block = 0; block < 2; ++block)
      for (const Part& p : parts)
        for (std::size_t v = 0; v < p.values; ++v)
          row += "," + p.rows[r][kShared + static_cast<std::size_t>(block) * p.values + v];
    out += row + "\n";
  }
  return out;
}

}  // namespace pelage::scene
