// Coverage-correct strands (as AMD TressFX and EA Frostbite draw hair): each hair segment becomes a
// screen-aligned quad of the hair's width at its two ends. The true width in pixels is the physical
// width (fur::StrandWidth, tapering root to tip) times the widening factor (c of sec. 3.3: a coat
// culled to 1/c of its hairs draws them c times wider, so it covers the same area) projected at the
// end's depth. A strand narrower than a pixel is drawn one pixel wide with its coverage (true width
// over drawn width) as alpha; the quad reaches half a pixel past the drawn width on each side, over
// which the fragment shader fades it (analytic edge anti-aliasing: the box-filtered coverage of a
// pixel by a band of the drawn width).
layout(lines) in;
layout(triangle_strip, max_vertices = 4) out;
in vec3 vPosition[];
in vec3 vShading[];
in float vAlong[];
in vec3 vColor[];
in float vWidthScale[];  // the hair's own multiple of the coat's width (1 without a groom's)
out vec3 gPosition;
out vec3 gShading;
out vec3 gColor;
flat out vec3 gTangent;  // the segment's direction (unit; 0 for a degenerate segment)
noperspective out float gEdge;       // signed distance from the centre line, pixels
noperspective out float gHalfWidth;  // half the drawn width, pixels
noperspective out float gCoverage;   // true width / drawn width
uniform vec2 uViewport;     // pixels
uniform float uRootWidth;   // metres
uniform float uTipWidth;    // metres
uniform float uWiden;       // >= 1
uniform float uProjScale;   // pixels per metre at clip w = 1: H / 2 * P[1][1]
void main() {
  vec4 c0 = gl_in[0].gl_Position;
  vec4 c1 = gl_in[1].gl_Position;
  if (c0.w <= 0.0 || c1.w <= 0.0) return;  // behind the eye: skip rather than flip
  vec2 s0 = c0.xy / c0.w * uViewport * 0.5;
  vec2 s1 = c1.xy / c1.w * uViewport * 0.5;
  vec2 d = s1 - s0;
  float len = length(d);
  vec2 n = len > 1e-6 ? vec2(-d.y, d.x) / len : vec2(1.0, 0.0);
  float t0 = uWiden * uProjScale * vWidthScale[0] * mix(uRootWidth, uTipWidth, vAlong[0]) / c0.w;
  float t1 = uWiden * uProjScale * vWidthScale[1] * mix(uRootWidth, uTipWidth, vAlong[1]) / c1.w;
  float h0 = 0.5 * max(t0, 1.0), h1 = 0.5 * max(t1, 1.0);
  float k0 = t0 / max(t0, 1.0), k1 = t1 / max(t1, 1.0);
  vec3 seg = vPosition[1] - vPosition[0];
  float segLen = length(seg);
  vec3 tangent = segLen > 0.0 ? seg / segLen : vec3(0.0);
  vec2 o0 = n * (h0 + 0.5) / (uViewport * 0.5) * c0.w;
  vec2 o1 = n * (h1 + 0.5) / (uViewport * 0.5) * c1.w;
  gTangent = tangent;
  gPosition = vPosition[0]; gShading = vShading[0]; gColor = vColor[0];
  gHalfWidth = h0; gCoverage = k0;
  gEdge = h0 + 0.5; gl_Position = vec4(c0.xy + o0, c0.zw); EmitVertex();
  gEdge = -(h0 + 0.5); gl_Position = vec4(c0.xy - o0, c0.zw); EmitVertex();
  gTangent = tangent;
  gPosition = vPosition[1]; gShading = vShading[1]; gColor = vColor[1];
  gHalfWidth = h1; gCoverage = k1;
  gEdge = h1 + 0.5; gl_Position = vec4(c1.xy + o1, c1.zw); EmitVertex();
  gEdge = -(h1 + 0.5); gl_Position = vec4(c1.xy - o1, c1.zw); EmitVertex();
  EndPrimitive();
}
