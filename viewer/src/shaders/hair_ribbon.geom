// Tapered ribbons: each hair segment becomes a screen-aligned quad whose width falls linearly
// from uRootWidth pixels at the root to 0 at the tip.
layout(lines) in;
layout(triangle_strip, max_vertices = 4) out;
in vec3 vPosition[];
in vec3 vShading[];
in float vAlong[];
in vec3 vColor[];
out vec3 gPosition;
out vec3 gShading;
out vec3 gColor;
uniform vec2 uViewport;    // pixels
uniform float uRootWidth;  // pixels
void main() {
  vec4 c0 = gl_in[0].gl_Position;
  vec4 c1 = gl_in[1].gl_Position;
  if (c0.w <= 0.0 || c1.w <= 0.0) return;  // behind the eye: skip rather than flip
  vec2 s0 = c0.xy / c0.w * uViewport * 0.5;
  vec2 s1 = c1.xy / c1.w * uViewport * 0.5;
  vec2 d = s1 - s0;
  float len = length(d);
  vec2 n = len > 1e-6 ? vec2(-d.y, d.x) / len : vec2(1.0, 0.0);
  float w0 = max(uRootWidth * (1.0 - vAlong[0]), 0.5) * 0.5;
  float w1 = max(uRootWidth * (1.0 - vAlong[1]), 0.5) * 0.5;
  vec2 o0 = n * w0 / (uViewport * 0.5) * c0.w;
  vec2 o1 = n * w1 / (uViewport * 0.5) * c1.w;
  gPosition = vPosition[0]; gShading = vShading[0]; gColor = vColor[0];
  gl_Position = vec4(c0.xy + o0, c0.zw); EmitVertex();
  gl_Position = vec4(c0.xy - o0, c0.zw); EmitVertex();
  gPosition = vPosition[1]; gShading = vShading[1]; gColor = vColor[1];
  gl_Position = vec4(c1.xy + o1, c1.zw); EmitVertex();
  gl_Position = vec4(c1.xy - o1, c1.zw); EmitVertex();
  EndPrimitive();
}
