// The plots of a gravity-response analysis (scene/analyze.h): the layout `pelage analyze --plot`
// and Python's analyze(plot=) draw, with scene/plot.h's renderer.
#pragma once

#include <string>

#include "pelage/scene/analyze.h"
#include "pelage/scene/model.h"
#include "pelage/scene/plot.h"

namespace pelage::scene {

// "pelage analyze: MODEL, clip CLIP, fur NAME, N hairs[, dynamics f0 F Hz, zeta Z]".
std::string analysisTitle(const Model& model, const Fur& fur, const AnalysisOptions& options);

// One run against time: the body's orientation; the mean droop angle, tip height and droop along
// the body's up axis, quasi-static (and dynamic, with the lag); with dynamics, the dynamic ends'
// distance from the quasi-static ones; a marker where the body stops (a hold).
PlotSpec analysisPlot(const AnalysisResult& result, const std::string& title);

// A sweep against time: the body's orientation, then the droop and tip height of every value (of
// the dynamic ends with dynamics, else of the quasi-static ones).
PlotSpec sweepPlot(const SweepResult& sweep, const std::string& title);

}  // namespace pelage::scene
