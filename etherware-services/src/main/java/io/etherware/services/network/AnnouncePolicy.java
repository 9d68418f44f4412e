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

    /** Whether node {@code nodeId} (authenticated, when links are TLS) may host {@code profile}. */
    boolean allows(String nodeId, Profile profile);

    /** Every connected node may announce any application profile: the default. */
    static AnnouncePolicy any() {
        return (nodeId, profile) -> true;
    }

    /** A policy of allow rules; a profile no rule allows is refused. */
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

        /** The policy; immutable. */
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
