/** The rotary inverted pendulum of the paper's Section VI-A, integrated with RK4. */
package io.etherware.pendulum.plant;
