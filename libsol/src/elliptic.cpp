#include "sol/elliptic.hpp"
