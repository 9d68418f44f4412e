package io.etherware.core.kernel;

import io.etherware.core.message.Contents;

/**
 * The kernel's marker for a route that moves (a component migrated): a node whose route to a
 * profile switches from one node to another sends a marker to the profile through the old node,
 * after every message it sent that way, and holds its later messages for the profile until the
 * marker has reached the component. The node where the marker reaches the component (it hosts it,
 * not relocating it) answers the marker's sender with {@code reached} set, as a reply to the
 * marker (its correlation id is the marker's id), and never gives the marker to the component; a
 * node that forwards the profile forwards the marker like any message to it, in order. Registered
 * as {@code route-marker}; see the management package documentation, "Why nothing is lost,
 * duplicated or reordered".
 *
 * @param reached false on the marker, true on the answer that it reached the component
 */
public record RouteMarker(boolean reached) implements Contents {
}
