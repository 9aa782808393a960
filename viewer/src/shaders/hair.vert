// Hair points from the coat's vertex buffers (written by the GPU fur pass or uploaded from the CPU
// fur model): position and shading vector (the style's shading normal, or the tangent for
// Kajiya-Kay). vAlong is the point's parameter along its hair (0 at the root, 1 at the tip).
layout(location = 0) in vec3 aPosition;
layout(location = 1) in vec3 aShading;
uniform mat4 uViewProj;
uniform int uPointsPerStrand;  // points along one hair (K for tubes: rings)
uniform int uStrandStride;     // 1, or M (ring size) for tubes
out vec3 vPosition;
out vec3 vShading;
out float vAlong;
void main() {
  vPosition = aPosition;
  vShading = aShading;
  int perHair = uPointsPerStrand * uStrandStride;
  int k = (gl_VertexID % perHair) / uStrandStride;
  vAlong = uPointsPerStrand > 1 ? float(k) / float(uPointsPerStrand - 1) : 0.0;
  gl_Position = uViewProj * vec4(aPosition, 1.0);
}
