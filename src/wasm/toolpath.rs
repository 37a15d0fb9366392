//! Bindings for the toolpath models. Written under the issue that implements them.
