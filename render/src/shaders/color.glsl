// Colour helpers shared by the hair and skin shaders: sRGB decoding (IEC 61966-2-1, as
// skin::srgbToLinear) and the packed hair colours of fur/colors.h (RGBA8, sRGB-encoded, R lowest).
vec3 srgbToLinear(vec3 c) {
  return mix(c / 12.92, pow((c + 0.055) / 1.055, vec3(2.4)), greaterThan(c, vec3(0.04045)));
}
vec3 unpackHairColor(uint p) {
  return srgbToLinear(vec3(float(p & 0xFFu), float((p >> 8) & 0xFFu), float((p >> 16) & 0xFFu)) /
                      255.0);
}
// A hair's width scale from the alpha bytes of its packed pair (fur/colors.h hairWidthScale: the
// 16-bit code, low byte in the root colour's, over kWidthScaleCodes).
float hairWidthScale(uvec2 pair) {
  return float((pair.x >> 24) | ((pair.y >> 24) << 8)) / 4096.0;
}
