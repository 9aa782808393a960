in vec3 vPosition;
in vec3 vNormal;
in vec2 vUv;
in vec4 vColor;
uniform bool uTextured;
layout(binding = 2) uniform sampler2D uBaseColor;  // sRGB texture: sampled linear
uniform vec3 uKs;
uniform float uShininess;
uniform float uShadowBias;
layout(location = 0) out vec4 fColor;
void main() {
  vec3 N = normalize(vNormal);
  if (!gl_FrontFacing) N = -N;
  vec3 base = vColor.rgb * (uTextured ? texture(uBaseColor, vUv).rgb : vec3(1.0));
  float s = shadowFactor(vPosition, uShadowBias);
  fColor = vec4(skinPassed(phong(N, vPosition, base, base, uKs, uShininess, s)), 1.0);
}
