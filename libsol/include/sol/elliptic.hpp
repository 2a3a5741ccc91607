// Jacobi elliptic functions and elliptic integrals (issue 3; being written).
#pragma once
