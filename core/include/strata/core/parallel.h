#pragma once
/// \file
/// Thread counts are passed explicitly, stage by stage (a Params field or an argument), never
/// through OpenMP's process-wide setting; every parallel loop is written so that its result
/// does not depend on the count.

namespace strata {

/// The team size for a parallel loop: \p requested if positive, else OpenMP's default (all
/// cores, unless OMP_NUM_THREADS says otherwise); 1 in a build without OpenMP.
int thread_count(int requested);

}  // namespace strata
