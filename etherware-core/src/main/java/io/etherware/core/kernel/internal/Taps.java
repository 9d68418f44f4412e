package io.etherware.core.kernel.internal;

import io.etherware.core.kernel.MessageTap;
import io.etherware.core.message.Message;
import java.util.ArrayList;
import java.util.Arrays;
import java.util.List;
import java.util.Objects;
import java.util.Set;
import java.util.concurrent.ConcurrentHashMap;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

/**
 * The node's {@link MessageTap}s. Telling them costs one volatile read when there is none.
 *
 * <p>Thread-safety: {@link #tell} from any thread without locking; changes serialized on this
 * object (copy-on-write).
 */
final class Taps {

    private static final Logger log = LoggerFactory.getLogger(Taps.class);

    private final String nodeId;
    private volatile MessageTap[] taps = new MessageTap[0];
    private final Set<MessageTap> failuresLogged = ConcurrentHashMap.newKeySet();

    Taps(String nodeId) {
        this.nodeId = nodeId;
    }

    /** Shows {@code message} to every tap; a tap that throws is logged once and changes nothing. */
    void tell(Message message) {
        MessageTap[] seeing = taps;
        if (seeing.length == 0) {
            return;
        }
        for (MessageTap tap : seeing) {
            try {
                tap.seen(message);
            } catch (RuntimeException e) {
                if (failuresLogged.add(tap)) {
                    log.warn("node {}: message tap {} threw (logged once; the message is delivered anyway)", nodeId,
                            tap, e);
                }
            }
        }
    }

    synchronized void add(MessageTap tap) {
        Objects.requireNonNull(tap, "tap");
        MessageTap[] next = Arrays.copyOf(taps, taps.length + 1);
        next[taps.length] = tap;
        taps = next;
    }

    synchronized boolean remove(MessageTap tap) {
        List<MessageTap> left = new ArrayList<>(Arrays.asList(taps));
        boolean removed = left.remove(tap);
        taps = left.toArray(MessageTap[]::new);
        return removed;
    }
}
