// Ground truth on the CPU, ray cast with Intel Embree: the brute-force RSM gather of [RSMV]'s
// Fig. 5.1d (every pixel light of the RSM at every G-buffer point, with exact visibility or
// without), and a one-bounce Monte Carlo reference that does not depend on the RSM (direct light
// plus one diffuse bounce of direct light, path traced). Deterministic for a seed (per-pixel
// hashes), multi-threaded. Both are long work: estimate_* say what a run costs (rays, and seconds
// from a calibration on this machine) before it starts, and a progress_monitor reports it and
// stops it at its deadline (frontend/core/progress.hpp). Every ray is checked before it reaches
// Embree (an Embree assertion aborts the process).
//
// One file each: the Embree scene and the camera's rays (ray_scene), the brute force
// (brute_force), the Monte Carlo reference (monte_carlo), and what their runs cost (work).
#pragma once

#include "frontend/reference/brute_force.hpp"
#include "frontend/reference/monte_carlo.hpp"
#include "frontend/reference/ray_scene.hpp"
#include "frontend/reference/work.hpp"
