#pragma once
// achd: the Popov-Vereshchagin hybrid dynamics solver. One include for everything.
#include "achd/case.hpp"
#include "achd/data.hpp"
#include "achd/dynamics.hpp"
#include "achd/error.hpp"
#include "achd/hybrid_dynamics.hpp"
#include "achd/kinematics.hpp"
#include "achd/model.hpp"
#include "achd/options.hpp"
#include "achd/pv_reference.hpp"
#include "achd/simulator.hpp"
#include "achd/spatial.hpp"
#include "achd/urdf.hpp"
