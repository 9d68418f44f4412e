/** Clocks of a node: monotonic time for scheduling, epoch time for message time stamps. */
package io.etherware.core.time;
