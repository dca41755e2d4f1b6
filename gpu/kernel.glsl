// Prism GPU kernels, part 3 of 3: the entry points. PRISM_MODE_TRACE builds
// the `prism trace` kernel (one invocation per ray, the same closest-hit
// code the renderer uses); otherwise one invocation renders one pixel of the
// current tile. The tile origin comes from PRISM_TILE_ORIGIN, which the
// backend defines (a uniform in OpenGL, a push constant in Vulkan).

layout(local_size_x = PRISM_LOCAL_SIZE_X, local_size_y = PRISM_LOCAL_SIZE_Y, local_size_z = 1) in;

#ifdef PRISM_MODE_TRACE

struct PrismTraceRay {
  wvec4 origin_tmin;
  wvec4 dir;
  wvec4 t_normal;
  ivec4 id;
  ivec4 pad;
};
layout(std430, binding = PRISM_BINDING_OUTPUT) buffer PrismTraceBuffer { PrismTraceRay prism_trace_rays[]; };

void main() {
  prism_fill_caches();  // first, before any branch: every lane writes it (see gpu/scene.glsl, "Caches")
  uint i = gl_GlobalInvocationID.x + uint(PRISM_TILE_ORIGIN.x);
  if (i >= uint(prism_frame.flags.y)) return;
  PrismWorldRay ray;
  ray.origin = prism_trace_rays[i].origin_tmin.xyz;
  ray.dir = prism_trace_rays[i].dir.xyz;
  PrismClosest hit = prism_closest(ray, prism_trace_rays[i].origin_tmin.w);
  wvec3 normal = wvec3(WL(0.0));
  if (hit.id >= 0) {
    normal = prism_world_surface(ray, hit).normal;
  } else if (hit.id != PRISM_MISS_ID) {  // a light sphere: its outward normal at the hit
    normal = normalize(ray.origin + hit.t * ray.dir - prism_light(-2 - hit.id).position.xyz);
  }
  prism_trace_rays[i].t_normal = wvec4(hit.t, normal);
  prism_trace_rays[i].id = ivec4(hit.id, 0, 0, 0);
}

#else

// The tile's pixels as planes of vec4, each as long as the tile: rgb and id
// first; then, only when prism_frame.flags.z asks for them, normal and path,
// and albedo and depth. A frame without those AOVs reads back 16 bytes a
// pixel.
layout(std430, binding = PRISM_BINDING_OUTPUT) buffer PrismOutputBuffer {
  uint prism_counters[8];
  vec4 prism_pixels[];
};

// The format's camera ray through pixel (i, j) at sample offset `offset`.
PrismWorldRay prism_camera_ray(int i, int j, wvec2 offset) {
  wreal width = wreal(prism_frame.size.x), height = wreal(prism_frame.size.y);
  wreal u = ((wreal(i) + offset.x) / width * WL(2.0) - WL(1.0)) * prism_frame.tan_half_fov * prism_frame.aspect;
  wreal v = (WL(1.0) - (wreal(j) + offset.y) / height * WL(2.0)) * prism_frame.tan_half_fov;
  PrismWorldRay ray;
  ray.origin = prism_frame.camera_position.xyz;
  ray.dir = normalize(prism_frame.camera_forward.xyz + u * prism_frame.camera_right.xyz + v * prism_frame.camera_up.xyz);
  return ray;
}

// The work group's block of the tile. Work groups are handed out in a
// scrambled order (group k renders block k * P mod n, P the prime the
// generator defines, above any group count, so the map is one to one): a
// CPU driver gives each thread a contiguous run of groups, and in row order
// one thread would get the sky while another gets the scene. gpu_dispatch.cpp
// checks that k * P stays below 2^32.
ivec2 prism_block() {
  uint n = gl_NumWorkGroups.x * gl_NumWorkGroups.y;
  uint k = (gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x) * PRISM_GROUP_SCRAMBLE % n;
  return ivec2(k % gl_NumWorkGroups.x, k / gl_NumWorkGroups.x);
}

void main() {
  ivec2 local = prism_block() * ivec2(gl_WorkGroupSize.xy) + ivec2(gl_LocalInvocationID.xy);
  ivec2 pixel = PRISM_TILE_ORIGIN.xy + local;
  prism_fill_caches();  // before any branch: every lane writes it (see gpu/scene.glsl, "Caches")
  if (local.x >= PRISM_TILE_ORIGIN.z || local.y >= PRISM_TILE_ORIGIN.w) return;
  for (int k = 0; k < PRISM_RAY_KINDS; ++k) prism_ray_counts[k] = 0u;
  // One loop runs the pixel's samples one after the other, each path one
  // interaction an iteration: code in a loop costs more than code outside
  // one on llvmpipe, and two loops nested cost more again (measured: a
  // frame at 1 spp costs 1.2x with a sample loop around the path's loop).
  // Samples are summed in order (as on the CPU), so the pixel never depends
  // on scheduling.
  vec3 sum = vec3(0.0);
  PrismSample first;
  int k = 0;
  prism_start_sample(k);
  PrismPathState st = prism_start_path(prism_camera_ray(pixel.x, pixel.y, prism_frame_buffer.sample_offsets[k]));
  for (;;) {
    if (prism_pass(st)) continue;
    st.result.radiance = st.radiance;
    st.result.path_hash = (prism_hash >> 24) ^ (prism_hash & 0xffffffu);  // folded to 24 bits: exact in a float
    if (k == 0) first = st.result;
    sum += st.radiance;
    if (++k == prism_frame.size.z) break;
    prism_start_sample(k);
    st = prism_start_path(prism_camera_ray(pixel.x, pixel.y, prism_frame_buffer.sample_offsets[k]));
  }
  uint index = uint(local.y * PRISM_TILE_ORIGIN.z + local.x);
  uint plane = uint(PRISM_TILE_ORIGIN.z * PRISM_TILE_ORIGIN.w);
  prism_pixels[index] = vec4(sum / float(prism_frame.size.z), float(first.first_id));
  if (prism_frame.flags.z != 0) {
    prism_pixels[plane + index] = vec4(vec3(first.first_normal), float(first.path_hash));
    prism_pixels[2u * plane + index] = vec4(first.first_albedo, float(first.first_t));
  }
  for (int k = 0; k < PRISM_RAY_KINDS; ++k)
    if (prism_ray_counts[k] != 0u) atomicAdd(prism_counters[k], prism_ray_counts[k]);
}

#endif
