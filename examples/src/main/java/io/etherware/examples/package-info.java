/** The paper's experiments as runnable scenarios, and the benchmark harness. */
package io.etherware.examples;
