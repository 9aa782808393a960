// The built-in monkey's procedural clips, chosen to show the fur's response to gravity
// (Van Gelder & Wilhelms 1997, sec. 3.5: the hair's ending point falls along world -Z whatever the
// body's orientation): `walk` (a quadrupedal lateral-sequence walk with planted feet), `tumble` (a
// slow forward roll: upside down mid-clip), `hang` (hanging from the left hand, swinging like a
// pendulum), `shake` (a quick wet-dog shake) and `idle` (breathing, looking around).
//
// Each clip is a smooth function of time over the whole real line: periodic, plus a constant drift
// of the root for the clips that travel. It is baked into a keyframed Clip (CUBICSPLINE, keys at
// 30 per second, tangents = the function's time derivative), so every clip - procedural, glTF or
// hand-authored - is played, blended and timed by one sampling path; the baked curve matches the
// function's value and velocity at every key, so the loop point is seamless in both.
#pragma once

#include <string>
#include <vector>

#include "pelage/anatomy/body.h"
#include "pelage/anatomy/creature.h"
#include "pelage/anatomy/pose.h"
#include "pelage/animation/clip.h"

namespace pelage::animation {

// The clip names, in the order they are attached to the monkey.
const std::vector<std::string>& monkeyClipNames();

// The first monkey segment `body` lacks (the clips drive the built-in monkey's named segments),
// or "" when it has them all.
std::string missingMonkeySegment(const anatomy::Body& body);

// One cycle's length (s) of procedural clip `name`; InputError for an unknown name.
double monkeyClipDuration(const std::string& name);

// The procedural clip `name` evaluated at time t (s, any real) for the creature's body: the pose,
// root drift included. The creature's body shapes keep the tumbling ball on the ground. InputError
// for an unknown name or a body without the monkey's segments.
void evaluateMonkeyClip(const anatomy::Creature& creature, const std::string& name, double t,
                        anatomy::Pose& pose);

// Bakes a procedural clip into a looping keyframed clip with root motion.
// keysPerSecond in [4, 240].
Clip bakeMonkeyClip(const anatomy::Creature& creature, const std::string& name,
                    int keysPerSecond = 30);

// All procedural clips, baked, in monkeyClipNames() order.
std::vector<Clip> monkeyClips(const anatomy::Creature& creature);

}  // namespace pelage::animation
