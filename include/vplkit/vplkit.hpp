// Every vplkit kernel in one include. Each header names its paper equation and its GLSL twin.
#pragma once

#include <vplkit/bilateral.hpp>
#include <vplkit/cube_map.hpp>
#include <vplkit/direct_light.hpp>
#include <vplkit/final_gather.hpp>
#include <vplkit/form_factor.hpp>
#include <vplkit/hash.hpp>
#include <vplkit/irradiance.hpp>
#include <vplkit/lightwave.hpp>
#include <vplkit/micro_linear_buffer.hpp>
#include <vplkit/polynomial_math.hpp>
#include <vplkit/rsm_gather.hpp>
#include <vplkit/rsm_packing.hpp>
#include <vplkit/rsm_pattern.hpp>
#include <vplkit/shading.hpp>
#include <vplkit/settings.hpp>
#include <vplkit/shadow.hpp>
#include <vplkit/transform.hpp>
#include <vplkit/version.hpp>
