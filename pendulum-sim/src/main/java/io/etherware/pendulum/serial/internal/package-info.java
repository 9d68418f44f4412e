/** Serial-link internals: the FFM pseudo-terminal used to test the real serial stack. Not API. */
package io.etherware.pendulum.serial.internal;
