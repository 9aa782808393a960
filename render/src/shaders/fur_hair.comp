// GPU fur, per frame: one invocation per root of a root window; the roots drawn after distance
// culling (sec. 3.3: the first k' roots of each triangle, in creation order) compute their hair with
// buildHair (hair_math.glsl, the mirror of the CPU model) and write its P points at their drawn slot
// i = drawnStart[t] + (j - triangleStart[t]), inside the output chunk bound at bindings 12/13.
// A clumped hair then moves toward its clump centre's strand points (generate.cpp addClump), and
// frizz comes last (addFrizz), in the CPU model's order.
layout(local_size_x = 64) in;

// (16 storage blocks: GL's guaranteed minimum for a compute shader, and llvmpipe's limit.)
layout(std430, binding = 1) readonly buffer Triangles { int triangles[]; };          // nT x 3
layout(std430, binding = 2) readonly buffer TriangleStart { int triangleStart[]; };  // nT + 1
layout(std430, binding = 3) readonly buffer DrawnStart { int drawnStart[]; };        // nT + 1
layout(std430, binding = 4) readonly buffer Roots { ivec4 roots[]; };  // window: (triangle, table index, length scale bits, packed comb)
layout(std430, binding = 5) readonly buffer Jitter { vec4 jitter[]; };               // window: (xi, phase)
// The coat's tables: the barycentric table (2048 x (b1, b2, b3, 0)), then from TWIST_FLOATS_AT
// the twist table (2048 x 8 x (cos, sin)).
layout(std430, binding = 6) readonly buffer Tables { float tables[]; };
layout(std430, binding = 7) readonly buffer RootExtras { ivec4 rootExtras[]; };      // window: (clump slot or -1, clump scale bits, floppiness bits, segment direction weight bits) [, (curl radius bits, curl turns bits, width scale bits, 0)]
layout(std430, binding = 8) readonly buffer Positions { float positions[]; };        // nV x 3, deformed
layout(std430, binding = 9) readonly buffer Normals { float normals[]; };            // nV x 3
layout(std430, binding = 10) readonly buffer VertexData { float vertexData[]; };     // nV x 3 directions, then nV lengths
layout(std430, binding = 11) readonly buffer ClumpCentres { float clumpCentres[]; };  // clumps x K x 3
layout(std430, binding = 12) buffer OutPositions { float outPositions[]; };          // chunk: C x P x 3
layout(std430, binding = 13) buffer OutShading { float outShading[]; };              // chunk: C x P x 3
layout(std430, binding = 16) readonly buffer RootColors { uvec2 rootColors[]; };     // window: (root, tip)
layout(std430, binding = 17) buffer OutColors { uvec2 outColors[]; };                // chunk: C

uniform int uWindowFirst;   // first root of the window (roots[0] is root uWindowFirst)
uniform int uWindowCount;   // roots in the window
uniform int uChunkFirst;    // first drawn slot of the output chunk
uniform int uChunkCount;    // drawn slots in the chunk
uniform bool uTangents;     // shading = unit tangents (Kajiya-Kay) instead of the style's normals
uniform int uStrandStride;  // 1, or M for tubes
uniform bool uColors;       // per-hair colours: copy each drawn hair's root and tip colour
uniform int uVertexCount;   // nV (where VertexData's lengths start)
uniform bool uClump;        // the coat clumps (RootExtras' clump and ClumpCentres are its)
uniform bool uRootExtras;   // RootExtras is bound (the coat clumps or has per-hair floppiness, w or curl)
uniform int uExtrasStride;  // ivec4s per root in RootExtras: 2 where the roots carry a groom's curl or width scale
uniform float uClumpWeights[MAX_CURVE_POINTS];  // fur::clumpWeights: s_k

int gOut = 0;    // first float of this hair's points in the chunk
uint gRoot = 0u;  // the hair's root index in the coat (its frizz seed)
bool gLater = false;  // clump and frizz after the hair is built (a clumped hair)

void emitPoint(int i, vec3 p, vec3 n) {
  int o = gOut + 3 * i;
  // Frizz (hair_math.h addFrizz): strand point i / frizzRing's offset on every point around it.
  if (cs.frizz != 0 && !gLater) p += frizzOffset(gRoot, i / cs.frizzRing);
  outPositions[o] = p.x;
  outPositions[o + 1] = p.y;
  outPositions[o + 2] = p.z;
  outShading[o] = n.x;
  outShading[o + 1] = n.y;
  outShading[o + 2] = n.z;
}

vec3 vertexArray3(int which, int v) {
  if (which == 0) return vec3(positions[3 * v], positions[3 * v + 1], positions[3 * v + 2]);
  if (which == 1) return vec3(normals[3 * v], normals[3 * v + 1], normals[3 * v + 2]);
  return vec3(vertexData[3 * v], vertexData[3 * v + 1], vertexData[3 * v + 2]);
}

vec3 outPoint(int i) {
  int o = gOut + 3 * i;
  return vec3(outPositions[o], outPositions[o + 1], outPositions[o + 2]);
}

void setOutPoint(int i, vec3 p) {
  int o = gOut + 3 * i;
  outPositions[o] = p.x;
  outPositions[o + 1] = p.y;
  outPositions[o + 2] = p.z;
}

// Clumping (generate.cpp addClump): every point of ring k of K moves by s_k scale (C_k - S_k), S_k
// the hair's own strand point (its ring's mean, in order; the point itself when M = 1), C_k its
// clump centre's (`slot`); the root ring stays.
void addClump(int slot, float scale) {
  int M = uStrandStride;
  int K = cs.points / M;
  for (int k = 1; k < K; ++k) {
    vec3 sum = vec3(0.0);
    for (int m = 0; m < M; ++m) sum += outPoint(k * M + m);
    vec3 own = M == 1 ? sum : sum / float(M);
    int c = (slot * K + k) * 3;
    vec3 centre = vec3(clumpCentres[c], clumpCentres[c + 1], clumpCentres[c + 2]);
    float wk = uClumpWeights[k] * scale;
    vec3 offset = wk * (centre - own);
    for (int m = 0; m < M; ++m) setOutPoint(k * M + m, outPoint(k * M + m) + offset);
  }
}

void main() {
  int local = int((gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x) * gl_WorkGroupSize.x +
                  gl_LocalInvocationID.x);
  if (local >= uWindowCount) return;
  int j = uWindowFirst + local;
  ivec4 r = roots[local];
  int t = r.x;
  int slot = drawnStart[t] + (j - triangleStart[t]);
  if (slot >= drawnStart[t + 1]) return;  // culled (sec. 3.3)
  if (slot < uChunkFirst || slot >= uChunkFirst + uChunkCount) return;  // another chunk's
  gOut = (slot - uChunkFirst) * cs.points * 3;
  gRoot = uint(j);
  if (uColors) outColors[slot - uChunkFirst] = rootColors[local];

  // Sec. 3.2: interpolate at the root with the table's barycentric coordinates.
  int v1 = triangles[3 * t], v2 = triangles[3 * t + 1], v3 = triangles[3 * t + 2];
  vec3 b = vec3(tables[4 * r.y], tables[4 * r.y + 1], tables[4 * r.y + 2]);
  int L = 3 * uVertexCount;  // the lengths
  HairInput hin = interpolateRoot(b, vertexArray3(0, v1), vertexArray3(0, v2),
                                  vertexArray3(0, v3), vertexData[L + v1], vertexData[L + v2], vertexData[L + v3],
                                  vertexArray3(1, v1), vertexArray3(1, v2), vertexArray3(1, v3),
                                  vertexArray3(2, v1), vertexArray3(2, v2), vertexArray3(2, v3),
                                  jitter[local], intBitsToFloat(r.z), r.w);
  for (int i = 0; i < POLYLINE_POINTS; ++i) {
    int w = TWIST_FLOATS_AT + 2 * (r.y * POLYLINE_POINTS + i);
    vec2 cs2 = cs.twist != 0 ? vec2(tables[w], tables[w + 1]) : vec2(1.0, 0.0);
    hin.twistCos[i] = cs2.x;
    hin.twistSin[i] = cs2.y;
  }
  // A groom's curl and width scale: a second ivec4 per root (uExtrasStride 2), read by curve and
  // tube coats (the curl) and tube coats (the width).
  ivec4 extras = uRootExtras ? rootExtras[uExtrasStride * local] : ivec4(-1, 0, 0, 0);
  if (cs.perHairCurl != 0 || cs.perHairWidth != 0) {
    ivec4 second = rootExtras[2 * local + 1];
    if (cs.perHairCurl != 0) {
      hin.curlRadius = intBitsToFloat(second.x);
      hin.curlTurns = intBitsToFloat(second.y);
    }
    if (cs.perHairWidth != 0) hin.widthScale = intBitsToFloat(second.z);
  }
  if (cs.perHairFloppiness != 0) hin.floppiness = intBitsToFloat(extras.z);
  if (cs.perHairSegmentWeight != 0) hin.segmentWeight = intBitsToFloat(extras.w);
  ivec2 clump = uClump ? extras.xy : ivec2(-1, 0);
  gLater = clump.x >= 0;
  buildHair(hin);
  if (gLater) {
    addClump(clump.x, intBitsToFloat(clump.y));
    if (cs.frizz != 0)
      for (int i = 0; i < cs.points; ++i) setOutPoint(i, outPoint(i) + frizzOffset(gRoot, i / cs.frizzRing));
  }

  if (uTangents) {
    // Kajiya-Kay's T: the direction of the segment leaving each point along its strand (the last
    // point repeats the one arriving), as the renderer computes it for CPU hairs.
    int M = uStrandStride;
    int K = cs.points / M;
    for (int k = 0; k < K; ++k)
      for (int m = 0; m < M; ++m) {
        int a = ((k + 1 < K) ? k : k - 1) * M + m, c = a + M;
        vec3 pa = vec3(outPositions[gOut + 3 * a], outPositions[gOut + 3 * a + 1], outPositions[gOut + 3 * a + 2]);
        vec3 pc = vec3(outPositions[gOut + 3 * c], outPositions[gOut + 3 * c + 1], outPositions[gOut + 3 * c + 2]);
        vec3 d = pc - pa;
        float len = length(d);
        d = len > 0.0 ? d / len : vec3(0.0, 0.0, 1.0);
        int o = gOut + 3 * (k * M + m);
        outShading[o] = d.x;
        outShading[o + 1] = d.y;
        outShading[o + 2] = d.z;
      }
  }
}
