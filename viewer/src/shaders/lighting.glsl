// Lighting shared by the skin and hair fragment shaders: one directional key light plus ambient,
// an optional shadow map, the paper's Phong model and the Kajiya-Kay hair model.
uniform vec3 uLightDir;      // world, unit, towards the light
uniform vec3 uLightColor;
uniform vec3 uAmbientLight;
uniform vec3 uEye;           // world camera position
uniform bool uShadows;
uniform mat4 uLightViewProj;
layout(binding = 0) uniform sampler2DShadow uShadowMap;

// Fraction of the key light reaching worldPos: 3x3 percentage-closer filtering of the shadow map.
float shadowFactor(vec3 worldPos, float bias) {
  if (!uShadows) return 1.0;
  vec4 p = uLightViewProj * vec4(worldPos, 1.0);
  vec3 q = p.xyz / p.w * 0.5 + 0.5;
  if (any(lessThan(q, vec3(0.0))) || any(greaterThan(q, vec3(1.0)))) return 1.0;
  vec2 texel = 1.0 / vec2(textureSize(uShadowMap, 0));
  float s = 0.0;
  for (int y = -1; y <= 1; ++y)
    for (int x = -1; x <= 1; ++x) s += texture(uShadowMap, vec3(q.xy + vec2(x, y) * texel, q.z - bias));
  return s / 9.0;
}

// The paper's lighting (sec. 3.2: "Hair is given a user-defined material type consisting of
// ambient, diffuse, and specular reflectivity", lit by the GL light model):
//   c = Ka La + s (Kd Ld max(N.L, 0) + Ks Ld max(N.H, 0)^shininess),  H = normalize(L + V),
// s the shadow factor. N is the shading normal each hair style defines (secs. 3.6 to 3.8).
vec3 phong(vec3 N, vec3 P, vec3 Ka, vec3 Kd, vec3 Ks, float shininess, float s) {
  vec3 V = normalize(uEye - P);
  vec3 H = normalize(uLightDir + V);
  float nl = max(dot(N, uLightDir), 0.0);
  float nh = nl > 0.0 ? max(dot(N, H), 0.0) : 0.0;
  return Ka * uAmbientLight + s * uLightColor * (Kd * nl + Ks * pow(nh, shininess));
}

// Kajiya & Kay 1989, "Rendering fur with three dimensional textures" (the paper's ref. [5]): a hair
// is a thin cylinder with unit tangent T;
//   diffuse  = Kd sin(T, L),
//   specular = Ks max(sin(T, L) sin(T, V) - (T.L)(T.V), 0)^shininess
// (brightest where V lies on the cone of mirror directions of L around T).
vec3 kajiyaKay(vec3 T, vec3 P, vec3 Ka, vec3 Kd, vec3 Ks, float shininess, float s) {
  vec3 V = normalize(uEye - P);
  float tl = dot(T, uLightDir);
  float tv = dot(T, V);
  float sinTL = sqrt(max(1.0 - tl * tl, 0.0));
  float sinTV = sqrt(max(1.0 - tv * tv, 0.0));
  float spec = pow(max(sinTL * sinTV - tl * tv, 0.0), shininess);
  return Ka * uAmbientLight + s * uLightColor * (Kd * sinTL + Ks * spec);
}
