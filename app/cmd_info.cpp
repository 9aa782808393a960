#include <cstdio>
#include <iostream>
#include <memory>

#include <nlohmann/json.hpp>

#include "commands.h"
#include "options.h"
#include "pelage/fur/coverage.h"
#include "pelage/fur/groom.h"
#include "pelage/skin/skin_mesh.h"

namespace pelage::app {

void printCoverage(const fur::FurCoverage& f) {
  for (int c = 0; c < fur::kCoatCount; ++c) {
    const fur::CoatCoverage& k = f.coats[static_cast<std::size_t>(c)];
    std::printf(
        "  %-9s  %.0f hairs, %.2f hairs/cm^2, mean length %.2f mm, mean width %.3f mm: optical "
        "depth %.3f\n",
        c == fur::kOvercoat ? "overcoat" : "undercoat", k.hairs, k.densityPerCm2, k.meanLengthMm,
        k.meanWidthMm, k.opticalDepth);
  }
  std::printf("  coverage   optical depth %.3f: %.1f %% of the skin hidden (expected)\n",
              f.opticalDepth, 100.0 * f.hiddenShare);
}

void addInfoCommand(CLI::App& app) {
  auto* cmd = app.add_subcommand("info", "Print a creature's segments, skin size, area and bounds");
  auto args = std::make_shared<ModelOptions>();
  auto furArgs = std::make_shared<FurOptions>();
  auto common = std::make_shared<CommonOptions>();
  auto json = std::make_shared<bool>(false);
  args->add(*cmd);
  furArgs->add(*cmd);
  common->add(*cmd, false);
  auto groomOut = std::make_shared<std::string>();
  cmd->add_flag("--json", *json, "Print machine-readable JSON");
  cmd->add_option("--groom-out", *groomOut,
                  "Write the per-vertex groom the fur would grow from (the --groom file's values "
                  "with the preset's regions applied, else the model's lengths) as a groom file: a "
                  "template to edit or to brush");
  cmd->callback([args, furArgs, json, groomOut] {
    const fur::FurParams asked = furArgs->resolve();  // bad options fail before the model loads
    const scene::Model m = args->load();
    // The preset's regions on this creature (a pattern that matches nothing is an error here).
    std::vector<fur::RegionMatch> matches;
    const fur::VertexGroom groom = fur::resolveVertexGroom(m.skin, m.body, m.name, asked,
                                                           "fur '" + asked.name + "'", &matches);
    if (!groomOut->empty()) {
      fur::VertexGroom out = groom;
      if (out.length.empty())
        out.length.assign(m.skin.furLengths(), m.skin.furLengths() + m.skin.numVertices());
      fur::writeGroomFile(*groomOut, m.skin, out);
    }
    const float* groomed = fur::groomedLengths(m.skin, groom);
    const fur::FurParams params = fur::fitCoverageToBudget(m.skin, asked, groomed);
    const fur::FurCoverage coverage = fur::estimateCoverage(m.skin, params, groomed, &groom);
    // Which regions grow fur: those with a vertex whose fur length is above 0.
    std::vector<bool> furred(m.skin.regionNames.size(), false);
    const float* lengths = m.skin.furLengths();
    const std::int32_t* regions = m.skin.regions();
    for (int v = 0; v < m.skin.numVertices(); ++v)
      if (lengths[v] > 0.0f && regions[v] >= 0 &&
          static_cast<std::size_t>(regions[v]) < furred.size())
        furred[static_cast<std::size_t>(regions[v])] = true;
    const skin::SkinStats s = skin::skinStats(m.skin);
    if (*json) {
      nlohmann::json j;
      j["name"] = m.name;
      j["source"] = m.source;
      j["vertices"] = s.vertices;
      j["triangles"] = s.triangles;
      j["areaSquareMeters"] = s.area;
      j["boundsMin"] = {s.boundsMin.x(), s.boundsMin.y(), s.boundsMin.z()};
      j["boundsMax"] = {s.boundsMax.x(), s.boundsMax.y(), s.boundsMax.z()};
      j["boundaryEdges"] = s.boundaryEdges;
      j["nonManifoldVertices"] = s.nonManifoldVertices;
      j["minAngleDegrees"] = s.minAngleDegrees;
      j["regions"] = m.skin.regionNames;
      nlohmann::json fur = nlohmann::json::array();
      for (std::size_t r = 0; r < furred.size(); ++r)
        if (furred[r]) fur.push_back(m.skin.regionNames[r]);
      j["furredRegions"] = fur;
      nlohmann::json segs = nlohmann::json::array();
      for (const auto& seg : m.body.segments) {
        nlohmann::json e;
        e["name"] = seg.name;
        e["parent"] =
            seg.parent < 0
                ? nlohmann::json(nullptr)
                : nlohmann::json(m.body.segments[static_cast<std::size_t>(seg.parent)].name);
        segs.push_back(e);
      }
      j["segments"] = segs;
      j["unitScale"] = m.unitScale;
      nlohmann::json clips = nlohmann::json::array();
      for (const auto& c : m.clips)
        clips.push_back({{"name", c.name},
                         {"durationSeconds", c.duration},
                         {"loop", c.loop},
                         {"channels", c.channels.size()}});
      j["clips"] = clips;
      nlohmann::json coats = nlohmann::json::array();
      for (const fur::CoatCoverage& k : coverage.coats)
        coats.push_back({{"hairs", k.hairs},
                         {"densityPerCm2", k.densityPerCm2},
                         {"meanLengthMm", k.meanLengthMm},
                         {"meanWidthMm", k.meanWidthMm},
                         {"opticalDepth", k.opticalDepth}});
      j["fur"] = {{"preset", params.name},
                  {"furredAreaSquareMeters", coverage.furredAreaM2},
                  {"coats", coats},
                  {"opticalDepth", coverage.opticalDepth},
                  {"hiddenShare", coverage.hiddenShare}};
      nlohmann::json regionsJson = nlohmann::json::array();
      for (const fur::RegionMatch& r : matches)
        regionsJson.push_back({{"match", r.pattern},
                               {"regions", r.regions},
                               {"joints", r.joints},
                               {"vertices", r.vertices}});
      j["fur"]["regions"] = regionsJson;
      std::cout << j.dump(2) << "\n";
      return;
    }
    std::printf("model      %s (%s)\n", m.name.c_str(), m.source.c_str());
    std::printf("skin       %d vertices, %d triangles, area %.4f m^2\n", s.vertices, s.triangles,
                s.area);
    std::printf("bounds     [%.4f %.4f %.4f] .. [%.4f %.4f %.4f] m\n",
                static_cast<double>(s.boundsMin.x()), static_cast<double>(s.boundsMin.y()),
                static_cast<double>(s.boundsMin.z()), static_cast<double>(s.boundsMax.x()),
                static_cast<double>(s.boundsMax.y()), static_cast<double>(s.boundsMax.z()));
    std::printf("topology   %d boundary edges, %d non-manifold vertices, min angle %.1f deg\n",
                s.boundaryEdges, s.nonManifoldVertices, s.minAngleDegrees);
    std::printf("regions   ");
    for (std::size_t r = 0; r < furred.size(); ++r)
      std::printf(" %s%s", m.skin.regionNames[r].c_str(), furred[r] ? "" : " (no fur)");
    std::printf("\nsegments   %d\n", m.body.size());
    for (const auto& seg : m.body.segments)
      std::printf("  %-20s parent %s\n", seg.name.c_str(),
                  seg.parent < 0
                      ? "-"
                      : m.body.segments[static_cast<std::size_t>(seg.parent)].name.c_str());
    if (m.unitScale != 1.0f)
      std::printf("units      %g m per file unit\n", static_cast<double>(m.unitScale));
    std::printf("clips      %zu\n", m.clips.size());
    for (const auto& c : m.clips)
      std::printf("  %-20s %.4f s%s\n", c.name.c_str(), static_cast<double>(c.duration),
                  c.loop ? "" : " (clamped)");
    std::printf("fur        %s over %.4f m^2 of furred skin\n", params.name.c_str(),
                coverage.furredAreaM2);
    printCoverage(coverage);
    for (const fur::RegionMatch& r : matches) {
      std::string names;
      for (const std::string& n : r.regions) names += (names.empty() ? "" : ", ") + n;
      for (const std::string& n : r.joints) names += (names.empty() ? "" : ", ") + n;
      std::printf("  region %-14s %d vertices: %s\n", ("'" + r.pattern + "'").c_str(), r.vertices,
                  names.c_str());
    }
  });
}

}  // namespace pelage::app
