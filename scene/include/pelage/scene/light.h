// The light of every frame: one directional key light plus ambient (the paper's OpenGL lighting),
// and the skin's material. GL-free.
#pragma once

#include <Eigen/Core>

#include <string_view>

#include "pelage/util/material.h"

namespace pelage::scene {

// The direction towards a light at azimuth (about +Z from +X) and elevation (above the XY plane),
// degrees.
Eigen::Vector3f lightDirection(float azimuthDegrees, float elevationDegrees);

// The key light's default place (the viewer's and every render's).
inline constexpr float kKeyLightAzimuthDegrees = 35.0f;
inline constexpr float kKeyLightElevationDegrees = 50.0f;

struct Light {
  // Towards the light (normalised by the renderer).
  Eigen::Vector3f direction = lightDirection(kKeyLightAzimuthDegrees, kKeyLightElevationDegrees);
  Eigen::Vector3f color{1.0f, 1.0f, 1.0f};
  Eigen::Vector3f ambient{0.35f, 0.35f, 0.35f};  // ambient light intensity (the paper's GL model)
  // Shadow map: the skin shadows itself and the fur (and, without self-shadowing, the hairs cast
  // hard shadows into it too).
  bool shadows = false;
  int shadowMapSize = 2048;
  // The fur's own soft shadow (deep opacity maps): the coat darkens inside by the hairs between
  // each point and the light, and the skin under it is shadowed by the fur.
  bool selfShadowing = true;
  int opacityMapSize = 512;  // its side in texels (the renderer clamps it to [64, 4096])
  // The share of the light a hair stops where it crosses the light's path, [0, 1]: hair fibres
  // scatter most of the light they meet on through the coat (mostly forward), so a dense coat is
  // lit deep inside, not black under its top layer. 1 = opaque fibres. 0.15 fitted on the key
  // light's part of the seven reference views against Cycles' (scripts/reference/views.py parts:
  // Cycles' luminance 0.83 to 1.16 times pelage's; 0.1 left pelage's 1.2 to 1.6 times too bright).
  float fibreOpacity = 0.15f;
  // The share of the key light a hair stops for the light the physical fur model's fibres scatter
  // themselves (lighting.glsl's fibre part: Chiang's scattering function, once and forward through
  // the coat), [0, 1], where fibreOpacity is the coat's: the light a fibre sends the eye straight
  // from the key light fades faster with the hairs in front than the coat's many-times-scattered
  // light does. 0.3 fitted on the reference views against Cycles' light passes (scripts/reference/
  // views.py passes, README: at 0.15 the light Cycles' fibres scatter once was 0.51 to 0.63 times
  // pelage's lit from behind; at 0.3, 0.93 to 1.22 times).
  float fibreLobeOpacity = 0.3f;
  // How far the physical fur model's coat spreads its direct light sideways, in hair lengths (the
  // standard deviation of the spread; transparent strands only): light scattered many times among
  // the hairs leaves the coat away from where it entered, so the body's shadow edges are soft and
  // shadowed fur beside lit fur is filled. 0 = none (every hair shaded where it is). 0.7 fitted
  // with fibreOpacity on the key light's part of the reference views (2 before: it spread the
  // light of the rim lit from behind far into the coat); 0.35 since the spread light follows the
  // skin's normal (coatSpreadSkinNormal), which gives the coat the body's light without a wide
  // spread: the fine detail kept (README: 18 of the 21 criteria against 16, mean MAE 10.48
  // against 10.40).
  float coatSpread = 0.35f;
  // How far the light the physical fur model's coat spreads sideways follows the skin's orientation
  // rather than each hair's, [0, 1]: that light's N.L (lighting.glsl's E) takes the normal of the
  // skin under the pixel (from its depth) mixed by this share into the hair's own (sec. 3.7's, in
  // its hair plane), where a hair keeps its own normal for the light it catches itself. Light
  // that has entered the coat and scattered among its hairs lights the coat as a layer over the
  // body: it falls off towards the body's terminator as the skin's light does, where the hairs'
  // own normals, tilted every way, catch as much light at the terminator as facing the light
  // (their N.L's mean is flat over the body's). 0 = the hairs' normals alone; the fringe beyond
  // the skin's outline keeps them. 1 fitted on the seven reference views against Cycles'
  // (README: Cycles' key light part over pelage's, by the skin's N.L, rose from 0.44-0.72 at the
  // terminator to 1.04-1.39 facing the light; mean MAE 10.62 -> 10.40).
  float coatSpreadSkinNormal = 1.0f;
  // How much of the physical fur model's ambient the coat loses where the eye looks along its
  // hairs, k_v: the coat's ambient is k_a La A (1 + k_v (0.35 - |T.V|)) (lighting.glsl), T the
  // hair's tangent: looking along the fibres the eye sees deeper into the coat, which the fibres
  // hide from the sky. 0 = the same from every side. 0.6 fitted on the ambient part of the
  // reference views against Cycles' (Cycles' over pelage's ambient, by each pixel's mean |T.V|:
  // up to 1.12 below 0.2, 0.64 to 0.89 above 0.8) and on the full frames.
  float alongFibreDarkening = 0.6f;
  // How much more saturated the physical fur model's ambient gets where the eye looks along the
  // coat's hairs, k_c: the coat's ambient colour is A's luminance times (A / its luminance) to the
  // power 1 + k_c (|T.V| - 0.35) (lighting.glsl), T the hair's tangent: looking along the fibres
  // the eye sees light that went deeper into the coat, through more fibres, each taking more of
  // the colours the hair absorbs; across them, light from the coat's top, paler. The hue and
  // (nearly) the luminance stay; a grey coat is unchanged. 0 = the same colour from every side.
  // 1.25 fitted on the seven reference views against Cycles' (README: Cycles' ambient part on the
  // Fox's back goes from blue/red 0.39 where |T.V| is 0.2 to 0.05 where it is 0.8).
  float alongFibreSaturation = 1.25f;
  // How much of the physical fur model's direct light the coat loses where the light runs along
  // its hairs, k_l: the coat's direct light is A s Ld k_n max(N.L, 0)^p max(1 + k_l (0.35 -
  // |T.L|), 0) (lighting.glsl, k_n = 0.8, p = 0.4; the light the coat spreads sideways too), T the
  // hair's tangent: light along the fibres passes between them deep into the coat, to the
  // self-shadowed depths and the skin, where across them the fibres' sides in the coat's top catch
  // it (the share of the light a fibre intercepts is its projected width, cos(theta_i)). 0 = the
  // same whatever the hairs' direction.
  // 2 fitted on the key light's part of the reference views against Cycles' (views.py parts: the
  // blurred key part's correlation with Cycles' 0.77 -> 0.83 over the six views) and on the full
  // frames with the coat's direct and ambient shares (README).
  float lightAlongFibreDarkening = 2.0f;
  // How much of the physical fur model's coat direct light the eye loses where it looks against
  // the light, k_b: the coat's direct light (and the light it spreads) is also multiplied by
  // max(1 - k_b max(-L.V, 0), 0) (lighting.glsl), V towards the eye: a coat lit from behind shows
  // the eye its fibres' unlit sides (the light scattered forward through the fibres is the fibre
  // lobes' part). 0 = the coat's direct light the same from every side; no change where the eye
  // and the light are on the same side (L.V >= 0). 0.7 fitted on the views lit from behind against
  // Cycles' (README: pelage lit a band 10 to 20 pixels wide inside the outline there, Cycles a
  // rim).
  float coatBacklitDarkening = 0.7f;
  // How deep the eye sees into the coat, in hair lengths (the longest hair's; transparent strands
  // only): a strand is seen through the strands in front of it, so the renderer weights it by
  // exp(d / (coatSeenDepth x hair length)), d its depth in front of the skin under its pixel
  // (hair.frag). 0 = every strand of the coat's depth counts alike (weighted blended OIT's plain
  // depth weights: the colours of the coat's depths, a darker leg's hairs behind a pale one's,
  // show through). 0.35 fitted on the seven reference views against Cycles' (README: their mean
  // MAE 12.60 -> 11.55, the ambient's shares k_a 0.66 -> 0.575 and k_g 0.6 -> 0.52 to keep the
  // luminance). Beyond the skin's outline d is measured from the nearest skin (renderer.cpp).
  float coatSeenDepth = 0.35f;
};

// The skin's lighting material (linear) for a typed, sRGB-encoded diffuse colour (the same ambient,
// small specular terms).
Material skinMaterial(const Eigen::Vector3f& color);
// Checks a key light's place: azimuth in [-360, 360], elevation in [-90, 90] degrees; InputError
// naming `field` ("light azimuth 400 is out of range [-360, 360]").
void validateLightAngles(float azimuthDegrees, float elevationDegrees,
                         std::string_view field = "light");

// The most a light's intensity may be per channel (Light::color, Light::ambient; linear).
inline constexpr float kMaxLightIntensity = 16.0f;
// Checks a light's intensity (linear R, G, B, each in [0, kMaxLightIntensity]); InputError naming
// `field` otherwise ("ambient G = -1 is out of range [0, 16]").
void validateLightIntensity(const Eigen::Vector3f& rgb, std::string_view field);

// Checks that each of r, g, b is in [0, 1] (a typed colour: skin, background); InputError naming
// `field` and the channel otherwise ("skin color G = 2 is out of range [0, 1]").
void validateColor(const Eigen::Vector3f& rgb, std::string_view field);

}  // namespace pelage::scene
