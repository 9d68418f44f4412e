package io.etherware.services.network;

import io.etherware.core.message.Profile;
import java.util.ArrayList;
import java.util.List;
import java.util.Objects;
import java.util.StringJoiner;
import java.util.regex.Pattern;

/**
 * Which application profiles a peer node may announce to this node, that is, draw the messages
 * sent here to them. Whatever the policy, a node may announce only its own node profile
 * ({@code etherware.node[id=...]}), a profile this node hosts itself stays local, and a profile
 * another node already announced stays routed there until that node withdraws it (a later claim
 * waits, and is logged): conflicts are never settled by node-id order.
 *
 * <p>Implementations are called on connection reader threads and must be thread-safe and quick.
 */
@FunctionalInterface
public interface AnnouncePolicy {

    /**
     * Whether node {@code nodeId} may host {@code profile}. Called on a connection's reader thread
     * for each announced profile; must not block.
     *
     * @param nodeId  the announcing node (authenticated, when links are TLS)
     * @param profile the application profile it announced
     * @return true to route {@code profile} to that node, false to refuse (counted and logged)
     */
    boolean allows(String nodeId, Profile profile);

    /**
     * Every connected node may announce any application profile: the default.
     *
     * @return a policy that allows everything
     */
    static AnnouncePolicy any() {
        return (nodeId, profile) -> true;
    }

    /**
     * A policy of allow rules; a profile no rule allows is refused.
     *
     * @return a new builder without rules (it builds a policy that refuses everything)
     */
    static Builder builder() {
        return new Builder();
    }

    /**
     * Allow rules: a node id (or {@code *} for any) and a pattern over the profile's canonical text
     * ({@code role[key=value,...]}), where {@code *} stands for any characters. Not thread-safe.
     */
    final class Builder {
        private record Rule(String nodeId, Pattern profile, String text) {
        }

        private final List<Rule> rules = new ArrayList<>();

        Builder() {
        }

        /**
         * Lets {@code nodeId} ({@code *}: any node) announce profiles matching {@code profileGlob},
         * e.g. {@code allow("node-2", "controller*")}.
         *
         * @param nodeId      a node id, or {@code *} for any node
         * @param profileGlob a pattern over the profile's canonical text in which {@code *} stands
         *                    for any characters; not empty ({@code *} for every profile)
         * @return this builder
         * @throws IllegalArgumentException if {@code nodeId} is not a node id or {@code *}, or
         *                                  {@code profileGlob} is empty
         */
        public Builder allow(String nodeId, String profileGlob) {
            Objects.requireNonNull(nodeId, "nodeId");
            Objects.requireNonNull(profileGlob, "profileGlob");
            if (!nodeId.equals("*") && !Profile.isName(nodeId)) {
                throw new IllegalArgumentException("nodeId='" + nodeId + "' must be '*' or match "
                        + Profile.NAME_PATTERN);
            }
            if (profileGlob.isEmpty()) {
                throw new IllegalArgumentException("profileGlob='' matches nothing; use '*' for every profile");
            }
            var regex = new StringJoiner(".*");
            for (String literal : profileGlob.split("\\*", -1)) {
                regex.add(Pattern.quote(literal));
            }
            String expression = regex.toString();
            rules.add(new Rule(nodeId, Pattern.compile(expression), profileGlob));
            return this;
        }

        /**
         * The policy: a profile is allowed if any rule matches. Immutable and thread-safe.
         *
         * @return the policy of the rules added so far
         */
        public AnnouncePolicy build() {
            List<Rule> fixed = List.copyOf(rules);
            return new AnnouncePolicy() {
                @Override
                public boolean allows(String nodeId, Profile profile) {
                    String text = profile.toString();
                    for (Rule rule : fixed) {
                        if ((rule.nodeId.equals("*") || rule.nodeId.equals(nodeId))
                                && rule.profile.matcher(text).matches()) {
                            return true;
                        }
                    }
                    return false;
                }

                @Override
                public String toString() {
                    return "AnnouncePolicy" + fixed.stream().map(r -> r.nodeId + ":" + r.text).toList();
                }
            };
        }
    }
}
