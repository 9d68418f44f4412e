/**
 * The Notifier's machinery: the release schedule and its skip rule, per-subscription state and
 * accounting, and the sleeper. Not exported; the API is {@link io.etherware.services.notifier}.
 */
package io.etherware.services.notifier.internal;
