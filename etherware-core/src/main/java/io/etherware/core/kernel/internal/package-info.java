/**
 * The kernel's machinery, not exported: {@link io.etherware.core.kernel.internal.KernelCore} (send,
 * job runner, requests, supervision, lifecycle), {@link io.etherware.core.kernel.internal.LocalShell}
 * with its {@link io.etherware.core.kernel.internal.ComponentGate}, the copy-on-write
 * {@link io.etherware.core.kernel.internal.ProfileTable}, the request table and the dispatcher mark
 * (a thread-local flag set on a thread the first time it runs a job, whichever scheduler owns it).
 */
package io.etherware.core.kernel.internal;
