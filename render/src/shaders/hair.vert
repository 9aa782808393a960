// Hair points from the coat's vertex buffers (written by the GPU fur pass or uploaded from the CPU
// fur model): position and shading vector (the style's shading normal, or the tangent for
// Kajiya-Kay). vAlong is the point's parameter along its hair (0 at the root, 1 at the tip); with
// per-hair colours, vColor is the hair's colour there, graded from its root colour to its tip colour
// (fur/colors.h), read from the coat's colour buffer by the hair's slot (gl_VertexID includes the
// chunk's base vertex, so the slot is global). With uPerHairWidth, vWidthScale is the hair's width
// scale from the same pair (fur/colors.h packHairWidth), else 1.
layout(location = 0) in vec3 aPosition;
layout(location = 1) in vec3 aShading;
uniform mat4 uViewProj;
uniform int uPointsPerStrand;  // points along one hair (K for tubes: rings)
uniform int uStrandStride;     // 1, or M (ring size) for tubes
uniform bool uPerHairColor;
uniform bool uPerHairWidth;
layout(binding = 1) uniform usamplerBuffer uHairColors;  // per slot: (root, tip)
out vec3 vPosition;
out vec3 vShading;
out float vAlong;
out vec3 vColor;
out float vWidthScale;
void main() {
  vPosition = aPosition;
  vShading = aShading;
  int perHair = uPointsPerStrand * uStrandStride;
  int k = (gl_VertexID % perHair) / uStrandStride;
  vAlong = uPointsPerStrand > 1 ? float(k) / float(uPointsPerStrand - 1) : 0.0;
  vColor = vec3(0.0);
  vWidthScale = 1.0;
  if (uPerHairColor) {
    uvec2 c = texelFetch(uHairColors, gl_VertexID / perHair).xy;
    vColor = mix(unpackHairColor(c.x), unpackHairColor(c.y), vAlong);
    if (uPerHairWidth) vWidthScale = hairWidthScale(c);
  }
  gl_Position = uViewProj * vec4(aPosition, 1.0);
}
