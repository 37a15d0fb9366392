//! Bindings for the kinematics models. Written under the issue that implements them.
