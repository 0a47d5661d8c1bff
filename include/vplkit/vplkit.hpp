// Every vplkit kernel in one include. Each header names its paper equation and its GLSL twin.
#pragma once

#include <vplkit/direct_light.hpp>
#include <vplkit/hash.hpp>
#include <vplkit/irradiance.hpp>
#include <vplkit/micro_linear_buffer.hpp>
#include <vplkit/version.hpp>
