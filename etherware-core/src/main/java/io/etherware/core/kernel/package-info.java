/**
 * The kernel of a node (paper Section III-A, Fig. 2): {@link io.etherware.core.kernel.EtherwareNode}
 * with its {@link io.etherware.core.kernel.NodeConfig}, the {@link io.etherware.core.kernel.Kernel}
 * mechanism that services use, the {@link io.etherware.core.kernel.ProfileRegistry} with local and
 * {@link io.etherware.core.kernel.RemoteRoute remote} endpoints, supervision policies, and the
 * kernel's notices {@link io.etherware.core.kernel.Undeliverable} and
 * {@link io.etherware.core.kernel.RequestFailed}. The machinery lives in the unexported
 * {@code internal} package.
 */
package io.etherware.core.kernel;
