package io.etherware.core.kernel.internal;

import io.etherware.core.kernel.Endpoint;
import io.etherware.core.kernel.ProfileRegistry;
import io.etherware.core.kernel.ProfileResolutionException;
import io.etherware.core.kernel.RemoteRoute;
import io.etherware.core.message.Profile;
import java.util.ArrayList;
import java.util.Collections;
import java.util.Comparator;
import java.util.HashMap;
import java.util.LinkedHashSet;
import java.util.List;
import java.util.Map;
import java.util.Objects;
import java.util.Set;
import java.util.concurrent.ConcurrentHashMap;
import java.util.concurrent.CopyOnWriteArrayList;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

/**
 * The {@link ProfileRegistry}: a copy-on-write table, so resolution on every send is a volatile
 * read and a hash lookup, without locks. Successful query resolutions are cached per table
 * version (a change of the table starts a new cache).
 *
 * <p>Thread-safety: lookups from any thread without locking; changes serialized on this object,
 * and listeners are called within that serialization.
 */
public final class ProfileTable implements ProfileRegistry {

    private static final Logger log = LoggerFactory.getLogger(ProfileTable.class);

    /** Queries cached per table version; a bound keeps hostile input from growing it forever. */
    private static final int MAX_CACHED_QUERIES = 1024;
    private static final int MAX_NAMED_CANDIDATES = 8;

    private record Table(Map<Profile, Endpoint> exact, ConcurrentHashMap<Profile, Endpoint> queries) {
        Table(Map<Profile, Endpoint> exact) {
            this(exact, new ConcurrentHashMap<>());
        }
    }

    private volatile Table table = new Table(Map.of());
    private final List<Listener> listeners = new CopyOnWriteArrayList<>();

    /** The endpoint {@code profile} resolves to, or null (then {@link #explainMiss} says why). */
    public Endpoint lookup(Profile profile) {
        Table current = table;
        Endpoint endpoint = current.exact.get(profile);
        if (endpoint != null) {
            return endpoint;
        }
        endpoint = current.queries.get(profile);
        if (endpoint != null) {
            return endpoint;
        }
        Endpoint only = null;
        for (Map.Entry<Profile, Endpoint> entry : current.exact.entrySet()) {
            if (entry.getKey().matches(profile)) {
                if (only != null) {
                    return null;
                }
                only = entry.getValue();
            }
        }
        if (only != null && current.queries.size() < MAX_CACHED_QUERIES) {
            current.queries.put(profile, only);
        }
        return only;
    }

    @Override
    public Endpoint resolve(Profile profile) {
        Objects.requireNonNull(profile, "profile");
        Endpoint endpoint = lookup(profile);
        if (endpoint == null) {
            throw new ProfileResolutionException(profile, candidates(profile), explainMiss(profile));
        }
        return endpoint;
    }

    /** Why {@code profile} does not resolve: no match, or ambiguous naming the candidates. */
    public String explainMiss(Profile profile) {
        List<Profile> candidates = candidates(profile);
        if (candidates.isEmpty()) {
            return "no component matches profile '" + profile + "'";
        }
        if (candidates.size() == 1) {
            return "profile '" + profile + "' resolves to '" + candidates.getFirst() + "' now";
        }
        var names = new StringBuilder();
        for (int i = 0; i < Math.min(candidates.size(), MAX_NAMED_CANDIDATES); i++) {
            names.append(i == 0 ? "" : ", ").append('\'').append(candidates.get(i)).append('\'');
        }
        if (candidates.size() > MAX_NAMED_CANDIDATES) {
            names.append(" and ").append(candidates.size() - MAX_NAMED_CANDIDATES).append(" more");
        }
        return "profile query '" + profile + "' is ambiguous: it matches " + names
                + "; add attributes to select one";
    }

    private List<Profile> candidates(Profile profile) {
        Table current = table;
        if (current.exact.containsKey(profile)) {
            return List.of(profile);
        }
        var candidates = new ArrayList<Profile>();
        for (Profile registered : current.exact.keySet()) {
            if (registered.matches(profile)) {
                candidates.add(registered);
            }
        }
        candidates.sort(Comparator.comparing(Profile::toString));
        return candidates;
    }

    @Override
    public Set<Profile> profiles() {
        return Collections.unmodifiableSet(new LinkedHashSet<>(table.exact.keySet()));
    }

    @Override
    public void registerRemote(Profile profile, RemoteRoute route) {
        register(profile, new Endpoint.Remote(Objects.requireNonNull(route, "route")));
    }

    @Override
    public synchronized boolean unregisterRemote(Profile profile) {
        Objects.requireNonNull(profile, "profile");
        Endpoint existing = table.exact.get(profile);
        if (existing == null) {
            return false;
        }
        if (!(existing instanceof Endpoint.Remote)) {
            throw new IllegalArgumentException("profile '" + profile
                    + "' belongs to a local component; remove the component from the node instead");
        }
        return unregister(profile, existing);
    }

    @Override
    public synchronized boolean replaceRemote(Profile profile, RemoteRoute expected, RemoteRoute replacement) {
        Objects.requireNonNull(profile, "profile");
        Objects.requireNonNull(replacement, "replacement");
        return table.exact.get(profile) instanceof Endpoint.Remote existing && existing.route() == expected
                && replace(profile, existing, new Endpoint.Remote(replacement));
    }

    @Override
    public void addListener(Listener listener) {
        listeners.add(Objects.requireNonNull(listener, "listener"));
    }

    @Override
    public boolean removeListener(Listener listener) {
        return listeners.remove(listener);
    }

    /**
     * Adds an endpoint. A local endpoint displaces a remote route registered for the same profile:
     * the component here wins over what a transport learned from elsewhere.
     *
     * @throws IllegalArgumentException if the profile is already registered to a local component,
     *                                  or a remote route is registered over an existing endpoint
     */
    public synchronized void register(Profile profile, Endpoint endpoint) {
        Objects.requireNonNull(profile, "profile");
        Objects.requireNonNull(endpoint, "endpoint");
        Endpoint existing = table.exact.get(profile);
        if (existing != null && !(existing instanceof Endpoint.Remote && endpoint instanceof Endpoint.Local)) {
            throw new IllegalArgumentException("profile '" + profile + "' is already registered ("
                    + (existing instanceof Endpoint.Local ? "a local component" : "a remote route")
                    + "); each profile names one component");
        }
        if (existing != null) {
            // Debug: a migration's arrival does this inside its pause, where a console line costs.
            log.debug("profile '{}': the local component displaces the remote route registered for it", profile);
        }
        var copy = new HashMap<>(table.exact);
        copy.put(profile, endpoint);
        table = new Table(copy);
        changed(profile, existing, endpoint);
    }

    /** Points {@code profile} at {@code replacement} if it still maps to {@code expected}. */
    public synchronized boolean replace(Profile profile, Endpoint expected, Endpoint replacement) {
        Objects.requireNonNull(replacement, "replacement");
        if (table.exact.get(profile) != expected) {
            return false;
        }
        var copy = new HashMap<>(table.exact);
        copy.put(profile, replacement);
        table = new Table(copy);
        changed(profile, expected, replacement);
        return true;
    }

    /** Removes {@code profile} if it still maps to {@code expected}; returns whether it did. */
    public synchronized boolean unregister(Profile profile, Endpoint expected) {
        if (table.exact.get(profile) != expected) {
            return false;
        }
        var copy = new HashMap<>(table.exact);
        copy.remove(profile);
        table = new Table(copy);
        changed(profile, expected, null);
        return true;
    }

    /** Tells the listeners of a change (called with the table's lock held, in change order). */
    private void changed(Profile profile, Endpoint before, Endpoint after) {
        for (Listener listener : listeners) {
            try {
                listener.onChanged(profile, before, after);
            } catch (RuntimeException e) {
                log.warn("profile registry listener {} failed on the change of '{}'", listener, profile, e);
            }
        }
    }
}
