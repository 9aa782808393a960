// Hair points seen from the light for the deep opacity map (deep_opacity.frag): the position and
// where the point lies along its hair (0 at the root, 1 at the tip; as hair.vert).
layout(location = 0) in vec3 aPosition;
uniform mat4 uViewProj;
uniform int uPointsPerStrand;  // points along one hair (K for tubes: rings)
uniform int uStrandStride;     // 1, or M (ring size) for tubes
out float vAlong;
void main() {
  int k = (gl_VertexID % (uPointsPerStrand * uStrandStride)) / uStrandStride;
  vAlong = uPointsPerStrand > 1 ? float(k) / float(uPointsPerStrand - 1) : 0.0;
  gl_Position = uViewProj * vec4(aPosition, 1.0);
}
