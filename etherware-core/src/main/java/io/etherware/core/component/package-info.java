/**
 * The component model (paper Section III-B): {@link io.etherware.core.component.Component}, the
 * logic a user writes; {@link io.etherware.core.component.ComponentState}, its state as a
 * registered record; {@link io.etherware.core.component.ComponentContext}, what it may do; and
 * {@link io.etherware.core.component.Shell}, the kernel's read-only view of it. Nothing here
 * depends on the kernel, so components compile against this package alone.
 */
package io.etherware.core.component;
