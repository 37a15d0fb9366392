//! ISO 10791-6 cone-frustum ball-bar test (kato-cone-frustum-ballbar).
//! Written under issue 6.
