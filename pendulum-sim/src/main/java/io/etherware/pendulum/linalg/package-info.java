/**
 * Dense linear algebra for controller design on small matrices: products and solves, the matrix
 * exponential, and eigenvalues. Design-time code: pure functions, thread-safe, not for hot paths.
 */
package io.etherware.pendulum.linalg;
