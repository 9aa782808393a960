#ifdef RIBBON
in vec3 gPosition;
in vec3 gShading;
in vec3 gColor;
#define P_IN gPosition
#define S_IN gShading
#define C_IN gColor
#else
in vec3 vPosition;
in vec3 vShading;
in vec3 vColor;
#define P_IN vPosition
#define S_IN vShading
#define C_IN vColor
#endif
uniform vec3 uKa;
uniform vec3 uKd;
uniform vec3 uKs;
uniform float uShininess;
uniform bool uKajiyaKay;
uniform bool uPerHairColor;  // the hair's colour is its diffuse, times uAmbientRatio its ambient
uniform float uAmbientRatio;
uniform float uShadowBias;
layout(location = 0) out vec4 fColor;
void main() {
  vec3 v = S_IN;
  float len = length(v);
  vec3 u = len > 0.0 ? v / len : vec3(0.0, 0.0, 1.0);
  float s = shadowFactor(P_IN, uShadowBias);
  vec3 kd = uPerHairColor ? C_IN : uKd;
  vec3 ka = uPerHairColor ? C_IN * uAmbientRatio : uKa;
  vec3 c = uKajiyaKay ? kajiyaKay(u, P_IN, ka, kd, uKs, uShininess, s)
                      : phong(u, P_IN, ka, kd, uKs, uShininess, s);
  fColor = vec4(c, 1.0);
}
