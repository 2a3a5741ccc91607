// libsol: the whole public API.
#pragma once

#include "sol/closed_form.hpp"
#include "sol/connection.hpp"
#include "sol/distance.hpp"
#include "sol/elliptic.hpp"
#include "sol/error.hpp"
#include "sol/group.hpp"
#include "sol/geodesic.hpp"
#include "sol/lattice.hpp"
#include "sol/observer.hpp"
#include "sol/render.hpp"
#include "sol/scene.hpp"
#include "sol/version.hpp"
