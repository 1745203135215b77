// The table of host services handed to block programs (defined in host_services.cpp).
#pragma once

#include "simcore/blockcode.h"

namespace simcore {
extern const vs_host_api kHostApi;
}
