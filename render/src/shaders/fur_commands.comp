// GPU fur, per frame: one indirect draw command per output chunk from the drawn total.
layout(local_size_x = 64) in;
layout(std430, binding = 3) readonly buffer DrawnStart { int drawnStart[]; };
struct DrawCommand {
  uint count;
  uint instanceCount;
  uint firstIndex;
  int baseVertex;
  uint baseInstance;
};
layout(std430, binding = 12) writeonly buffer Commands { DrawCommand commands[]; };
uniform int uTriangles;
uniform int uChunks;
uniform int uChunkCapacity;  // hairs per chunk (all but the last)
uniform int uPointsPerHair;
uniform int uIndicesPerHair;
void main() {
  int c = int((gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x) * gl_WorkGroupSize.x + gl_LocalInvocationID.x);
  if (c >= uChunks) return;
  int total = drawnStart[uTriangles];
  int first = c * uChunkCapacity;
  int n = clamp(total - first, 0, uChunkCapacity);
  commands[c].count = uint(n * uIndicesPerHair);
  commands[c].instanceCount = 1u;
  commands[c].firstIndex = 0u;
  commands[c].baseVertex = first * uPointsPerHair;
  commands[c].baseInstance = 0u;
}
