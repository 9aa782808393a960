// Tutorial 102: how far a coat droops under gravity while its body tumbles.
//
//   102_droop [FRAMES]
//
// The built-in monkey's "tumble" clip turns it over; every hair's droop angle (between its ending
// point's direction and its weightless direction, Van Gelder & Wilhelms 1997, sec. 3.5) is measured
// per frame, for the paper's quasi-static hairs and for damped dynamic ends. Prints one line per
// frame: the body's tilt from upright and the coat's mean droop in both models.
#include <cstdio>
#include <exception>
#include <stdexcept>
#include <string>

#include "pelage/fur/preset.h"
#include "pelage/scene/analyze.h"
#include "pelage/scene/frame.h"
#include "pelage/scene/model.h"

int main(int argc, char** argv) {
  using namespace pelage;
  try {
    const int frames = argc > 1 ? std::stoi(argv[1]) : 31;
    scene::Model model = scene::loadModel("monkey");
    fur::FurParams params = fur::loadFurPreset("default");
    params.setHairCount(20000);
    const scene::Fur fur = scene::growFur(model, params);

    scene::AnalysisOptions options;
    options.clip = scene::resolveClip(model, "tumble");
    options.frames = {0, frames - 1, 1};
    options.dynamics = true;  // also the damped ends (fur/dynamics.h), springs at their defaults
    const scene::AnalysisResult result = scene::analyzeClip(model, fur, options);

    std::printf("frame  tilt_deg  droop_qs_deg  droop_dynamic_deg\n");
    for (const scene::FrameAnalysis& f : result.frames)
      std::printf("%5d  %8.1f  %12.2f  %17.2f\n", f.frame, f.tiltDeg,
                  f.quasiStatic.all.droopMeanDeg, f.dynamic.all.droopMeanDeg);
  } catch (const std::invalid_argument&) {  // std::stoi on an argument that is not a number
    std::fprintf(stderr, "usage: 102_droop [FRAMES]: FRAMES is a number\n");
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "102_droop: %s\n", e.what());
    return 1;
  }
  return 0;
}
