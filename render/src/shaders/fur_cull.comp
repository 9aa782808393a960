// GPU fur, per frame, distance culling (Van Gelder & Wilhelms 1997, sec. 3.3): triangle t with k
// roots draws k' = min(k, floor(k / c + u_t)) of them ("random rounding", u_t fixed per triangle and
// uploaded once), then a block-wise inclusive scan; fur_scan.comp adds the block offsets, giving
// drawnStart (nT + 1, CSR over drawn hairs) exactly as fur::computeDrawnStart does on the CPU.
layout(local_size_x = 256) in;
layout(std430, binding = 2) readonly buffer TriangleStart { int triangleStart[]; };  // nT + 1
layout(std430, binding = 3) buffer DrawnStart { int drawnStart[]; };                 // nT + 1
layout(std430, binding = 14) readonly buffer CullU { float cullU[]; };               // nT
layout(std430, binding = 15) buffer BlockSums { int blockSums[]; };                  // groups
uniform int uTriangles;
uniform float uFactor;  // c >= 1
shared int sScan[256];
void main() {
  int t = int(gl_GlobalInvocationID.x);
  int kd = 0;
  if (t < uTriangles) {
    int k = triangleStart[t + 1] - triangleStart[t];
    if (k > 0) kd = min(k, int(floor(float(k) / uFactor + cullU[t])));
  }
  uint l = gl_LocalInvocationID.x;
  sScan[l] = kd;
  barrier();
  for (uint off = 1u; off < 256u; off <<= 1) {
    int add = l >= off ? sScan[l - off] : 0;
    barrier();
    sScan[l] += add;
    barrier();
  }
  if (t < uTriangles) drawnStart[t + 1] = sScan[l];
  if (l == 255u) blockSums[gl_WorkGroupID.x] = sScan[255];
}
