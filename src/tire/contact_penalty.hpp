// Default contact penalties scaled from the structure's own stiffness (model:contact and
// a tire on its road without given penalties). They assemble and factorize the static
// tangent, so they live above the contact elements, with the solver layer.
#pragma once

#include <vector>

#include "contact/rigid_surface.hpp"
#include "solvers/analysis.hpp"

namespace tirefe {

/// Default normal penalty: factor x the largest diagonal entry of the structure's static
/// tangent dF_int/du on the u_x, u_y equations of the nodes, assembled at the analysis's
/// current state (the reference before the first step). Call it before adding the contact
/// block. Throws ModelError when the nodes carry no stiffness (give the penalty then).
double structural_penalty(Analysis& analysis, const std::vector<int>& nodes, double factor = 1.0);

/// Default tangential penalty: factor x the smallest tangential stiffness the structure
/// itself offers at the nodes, 1 / (tau^T C tau), with C the nodal block of the inverse of
/// the static tangent and tau the surface's tangent below the node. Above that stiffness a
/// slipping node (which has no tangential contact stiffness) can make Newton alternate
/// between slip directions. The structure must be supported without the contact (hold the
/// hub while defining it); otherwise throws ModelError (give the penalty then).
double structural_tangential_penalty(Analysis& analysis, const std::vector<int>& nodes, const RigidSurface& surface,
                                     double factor = 1.0);

}  // namespace tirefe
