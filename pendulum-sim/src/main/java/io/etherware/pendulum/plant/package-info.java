/**
 * The rotary inverted pendulum of the paper's Section VI-A: parameters, equation (1) as
 * {@code ẋ = f(x, u)}, its fixed-step RK4 integration, energy, and the linearization of
 * equation (2) about the upright equilibrium.
 */
package io.etherware.pendulum.plant;
