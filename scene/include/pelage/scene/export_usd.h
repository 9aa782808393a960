// Animated hair geometry as a USD ASCII layer (.usda), written one frame at a time with bounded
// memory: the skin as an animated Mesh and each coat (Van Gelder & Wilhelms 1997, sec. 3.1) as
// animated BasisCurves, with a time sample per frame. Lines and polylines (sec. 3.6, 3.7) are
// "linear" curves through their points; the curve style (sec. 3.8) is a "cubic" "bezier" curve with
// the paper's four control points (a piecewise Bezier through the tessellated points when curled);
// tubes are written as their centre curve with widths from the tube radius.
//
// Layout (USD's ordering: an attribute's time samples are consecutive): each animated attribute's
// samples go to a spool file beside the output as frames arrive; finish() assembles the layer from
// the spools into the output (a temporary file renamed when complete) and removes them. The spools
// are removed on every exit path: by the destructor (errors), by the signal handler of
// util/atomic_file.h (an interrupted run), and, after a SIGKILL, by the next run for the same
// output.
#pragma once

#include <cstdint>
#include <memory>
#include <string>

#include "pelage/fur/fur_params.h"
#include "pelage/scene/frame.h"
#include "pelage/scene/model.h"

namespace pelage::scene {

struct UsdExportOptions {
  double framesPerSecond = 30.0;  // timeCodesPerSecond; time code = frame number
  int firstFrame = 0;
  int lastFrame = 0;
  std::string comment;  // the layer's doc string
};

// What the layer holds.
struct UsdExportCounts {
  int frames = 0;
  int skinVertices = 0;
  int skinTriangles = 0;
  std::int64_t curves[fur::kCoatCount] = {0, 0};  // per coat
  int verticesPerCurve[fur::kCoatCount] = {0, 0};
};

class UsdaWriter {
 public:
  // Opens the spool files beside `path`; InputError naming `path` when its directory is not
  // writable. `fur` gives the styles, widths and each hair's colours (primvars:displayColor,
  // linear); it must stay valid until finish().
  UsdaWriter(std::string path, const Model& model, const Fur& fur, const UsdExportOptions& options);
  ~UsdaWriter();  // removes the spool files (and writes nothing) if finish() was not reached
  UsdaWriter(const UsdaWriter&) = delete;
  UsdaWriter& operator=(const UsdaWriter&) = delete;

  // Appends frame `frame` (in [firstFrame, lastFrame], increasing): the frame's deformed skin and
  // its CPU hairs (evaluateFur with cpuHairs and no culling: every root's hair each frame).
  // InputError naming the output on a write failure (disk full).
  void addFrame(int frame, const FrameState& state);

  // Writes the layer atomically and removes the spools. Frames not added are absent (USD holds the
  // nearest sample).
  UsdExportCounts finish();

  // Spool and temporary files of the same output that killed runs had left, removed on opening.
  int removedTemporaries() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// A valid USD identifier from `name` ([A-Za-z_][A-Za-z0-9_]*; others become '_').
std::string usdIdentifier(const std::string& name);

}  // namespace pelage::scene
