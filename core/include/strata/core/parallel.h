#pragma once
/// \file
/// Thread counts are passed explicitly, stage by stage (a Params field or an argument), never
/// through OpenMP's process-wide setting; every parallel loop is written so that its result
/// does not depend on the count.

namespace strata {

/// The team size for a parallel loop: \p requested if positive, else all cores (the processors
/// this process may run on, omp_get_num_procs), unless OMP_NUM_THREADS says otherwise (its first
/// count); 1 in a build without OpenMP. Fixed at the first call, whatever Gmsh or another
/// library later sets as OpenMP's default.
int thread_count(int requested);

/// The team size for a parallel loop over \p items independent items: thread_count(requested),
/// but 1 below kParallelItems, where the loop takes well under a millisecond alone and the
/// team's start and barrier would cost more than it saves. On a machine running more threads
/// than it has cores (a design loop running several Strata processes at once) a barrier
/// waits for a descheduled thread's time slice: the 14 triangles of a delta wing's STL took 21
/// to 55 s in the layer stage, 93 % of it in libgomp's barriers, instead of 0.08 s alone.
int thread_count(int requested, long long items);

/// InputError "<parameter> is <threads>: give 0 (all cores) or a positive count" for a negative
/// \p threads, which thread_count would silently take for all cores; each stage that takes a
/// count in its Params checks it, naming the field (\p parameter: "LayerParams::threads").
void check_threads(int threads, const char* parameter);

/// See thread_count(int, long long).
inline constexpr long long kParallelItems = 2048;

}  // namespace strata
