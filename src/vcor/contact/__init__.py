"""Impact set-up: the bodies (sphere, plate, rigid target) and their combination into the contact
kernel k(t), the sphere mass m and the plate mobility alpha(t) that the solvers march."""
