//! The C ABI (see include/pqp/pqp.h).
