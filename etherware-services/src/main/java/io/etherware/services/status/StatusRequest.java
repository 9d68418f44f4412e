package io.etherware.services.status;

import io.etherware.core.message.Contents;

/**
 * Asks a node's status service for a {@link NodeStatus}; wire name {@value Status#STATUS_REQUEST}.
 * Carries nothing.
 */
public record StatusRequest() implements Contents {
}
