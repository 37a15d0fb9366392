//! Bindings for the ballbar models. Written under the issue that implements them.
