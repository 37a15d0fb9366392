//! Bindings for the servo models. Written under the issue that implements them.
