// The skin in its own colours, one vertex per triangle corner: the corner's texture coordinates,
// its colour (the material's base colour x the vertex colour, linear RGBA) and its skin vertex,
// whose deformed position and normal come from the frame's skin arrays.
layout(location = 0) in vec2 aUv;
layout(location = 1) in vec4 aColor;
layout(location = 2) in int aVertex;
layout(std430, binding = 0) readonly buffer SkinPositions { float skinPositions[]; };
layout(std430, binding = 1) readonly buffer SkinNormals { float skinNormals[]; };
uniform mat4 uViewProj;
out vec3 vPosition;
out vec3 vNormal;
out vec2 vUv;
out vec4 vColor;
void main() {
  int o = 3 * aVertex;
  vPosition = vec3(skinPositions[o], skinPositions[o + 1], skinPositions[o + 2]);
  vNormal = vec3(skinNormals[o], skinNormals[o + 1], skinNormals[o + 2]);
  vUv = aUv;
  vColor = aColor;
  gl_Position = uViewProj * vec4(vPosition, 1.0);
}
