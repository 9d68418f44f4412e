/**
 * The kernel's machinery, not exported: {@link io.etherware.core.kernel.internal.KernelCore} (send,
 * job runner, lifecycle) with its parts: {@link io.etherware.core.kernel.internal.Delivery} (jobs,
 * routes, undeliverable notices), the request table, {@link io.etherware.core.kernel.internal.ShellTable}
 * (the hosted components), {@link io.etherware.core.kernel.internal.Supervision} (failure reports,
 * escalation), the reconfiguration steps and the message taps;
 * {@link io.etherware.core.kernel.internal.LocalShell} with its
 * {@link io.etherware.core.kernel.internal.ComponentGate}, its
 * {@link io.etherware.core.kernel.internal.ComponentLogic} (the logic, its lifecycle and restart
 * policy) and its queue of actions waiting for quiescence; the copy-on-write
 * {@link io.etherware.core.kernel.internal.ProfileTable} and the dispatcher mark (a thread-local flag
 * set on a thread the first time it runs a job, whichever scheduler owns it).
 */
package io.etherware.core.kernel.internal;
