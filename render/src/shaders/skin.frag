in vec3 vPosition;
in vec3 vNormal;
uniform vec3 uKa;
uniform vec3 uKd;
uniform vec3 uKs;
uniform float uShininess;
uniform float uShadowBias;
layout(location = 0) out vec4 fColor;
void main() {
  vec3 N = normalize(vNormal);
  if (!gl_FrontFacing) N = -N;
  float s = shadowFactor(vPosition, uShadowBias);
  fColor = vec4(skinPassed(phong(N, vPosition, uKa, uKd, uKs, uShininess, s)), 1.0);
}
