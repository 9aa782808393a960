// GPU fur, per frame: the second and third steps of the drawnStart scan (see fur_cull.comp).
// PASS 1 (one work group): exclusive scan of the block sums, 256 at a time with a carry.
// PASS 2: add each block's offset to its triangles; drawnStart[0] = 0.
layout(local_size_x = 256) in;
layout(std430, binding = 3) buffer DrawnStart { int drawnStart[]; };
layout(std430, binding = 15) buffer BlockSums { int blockSums[]; };
uniform int uTriangles;
uniform int uBlocks;
shared int sScan[256];
void main() {
#if PASS == 1
  uint l = gl_LocalInvocationID.x;
  int carry = 0;
  for (int base = 0; base < uBlocks; base += 256) {
    int i = base + int(l);
    int v = i < uBlocks ? blockSums[i] : 0;
    sScan[l] = v;
    barrier();
    for (uint off = 1u; off < 256u; off <<= 1) {
      int add = l >= off ? sScan[l - off] : 0;
      barrier();
      sScan[l] += add;
      barrier();
    }
    if (i < uBlocks) blockSums[i] = carry + sScan[l] - v;  // exclusive
    int total = sScan[255];
    barrier();
    carry += total;
  }
#else
  int t = int(gl_GlobalInvocationID.x);
  if (t == 0) drawnStart[0] = 0;
  if (t < uTriangles) drawnStart[t + 1] += blockSums[gl_WorkGroupID.x];
#endif
}
