// layerjkr: umbrella header - adhesive (JKR) contact of thin elastic layers.
#pragma once

#include "layerjkr/contact.hpp"
#include "layerjkr/context.hpp"
#include "layerjkr/curve_data.hpp"
#include "layerjkr/discrete.hpp"
#include "layerjkr/error.hpp"
#include "layerjkr/exact_layer.hpp"
#include "layerjkr/fit.hpp"
#include "layerjkr/instrument.hpp"
#include "layerjkr/jkr.hpp"
#include "layerjkr/model.hpp"
#include "layerjkr/model_choice.hpp"
#include "layerjkr/model_error.hpp"
#include "layerjkr/model_spec.hpp"
#include "layerjkr/profile.hpp"
#include "layerjkr/scene.hpp"
#include "layerjkr/simulate.hpp"
