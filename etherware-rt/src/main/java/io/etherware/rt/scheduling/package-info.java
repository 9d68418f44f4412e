/** The real-time Dispatching Module: dispatchers at fixed OS priorities, the Job Placement Rule and the Thread Scheduling Rule (paper Section IV-B). */
package io.etherware.rt.scheduling;
