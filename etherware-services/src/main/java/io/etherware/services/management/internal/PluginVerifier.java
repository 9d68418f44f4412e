package io.etherware.services.management.internal;

import io.etherware.services.management.ManagementFailure.Reason;
import java.io.IOException;
import java.io.InputStream;
import java.nio.file.Files;
import java.nio.file.Path;
import java.nio.file.StandardCopyOption;
import java.security.CodeSigner;
import java.security.GeneralSecurityException;
import java.security.cert.CertPathValidator;
import java.security.cert.CertificateExpiredException;
import java.security.cert.CertificateFactory;
import java.security.cert.CertificateNotYetValidException;
import java.security.cert.PKIXCertPathValidatorResult;
import java.security.cert.PKIXParameters;
import java.security.cert.TrustAnchor;
import java.security.cert.X509Certificate;
import java.util.ArrayList;
import java.util.Date;
import java.util.HashMap;
import java.util.LinkedHashSet;
import java.util.List;
import java.util.Locale;
import java.util.Map;
import java.util.Set;
import java.util.jar.JarEntry;
import java.util.jar.JarFile;

/**
 * Checks that a plugin jar is signed, entirely, by a key the node trusts: copies it to a private
 * file (so it cannot change between the check and the loading), opens the copy with
 * verification, reads every entry fully (a digest that does not match throws), and requires each
 * class and resource (every entry but the manifest and the signature files in {@code META-INF/})
 * to carry a code signer whose certificate is trusted or whose chain validates (PKIX, no
 * revocation check) up to a trusted certificate, every certificate valid now.
 *
 * <p>Thread-safety: immutable; any thread. Reads and writes files: call it off the dispatchers.
 */
final class PluginVerifier {

    private static final int LISTED = 3;

    private final List<X509Certificate> trusted;

    PluginVerifier(List<X509Certificate> trusted) {
        this.trusted = List.copyOf(trusted);
    }

    /**
     * A private copy of {@code jar}, verified; the caller loads from it and deletes it when done.
     *
     * @throws LoadFailure {@link Reason#UNTRUSTED_CODE} naming the jar and what is wrong with its
     *                     signature, or {@link Reason#CLASS_NOT_LOADABLE} if it cannot be read
     */
    Path verifiedCopy(Path jar) throws LoadFailure {
        if (trusted.isEmpty()) {
            throw new LoadFailure(Reason.UNTRUSTED_CODE, "jar '" + jar + "' is refused: this node trusts no plugin"
                    + " signer, and plugins must be signed; sign the jar with jarsigner and trust the signing"
                    + " certificate with ManagementConfig.builder().trustStore(pkcs12Path, password) (or"
                    + " trustedSigners(keyStore), trustedSigner(certificate))");
        }
        Path copy;
        try {
            copy = Files.createTempFile("etherware-plugin-", ".jar"); // owner-only where POSIX
            copy.toFile().deleteOnExit();
            Files.copy(jar, copy, StandardCopyOption.REPLACE_EXISTING);
        } catch (IOException e) {
            throw new LoadFailure(Reason.CLASS_NOT_LOADABLE, "jar '" + jar + "' cannot be copied for verification: "
                    + e, e);
        }
        try {
            verify(copy, jar);
            return copy;
        } catch (LoadFailure | RuntimeException e) {
            deleteQuietly(copy);
            throw e;
        }
    }

    private void verify(Path copy, Path jar) throws LoadFailure {
        Date now = new Date();
        List<String> unsigned = new ArrayList<>();
        Set<String> distrusted = new LinkedHashSet<>();
        Map<CodeSigner, String> verdicts = new HashMap<>();
        int signed = 0;
        byte[] buffer = new byte[8192];
        try (JarFile file = new JarFile(copy.toFile(), true)) {
            for (JarEntry entry : file.stream().toList()) {
                if (entry.isDirectory()) {
                    continue;
                }
                try (InputStream in = file.getInputStream(entry)) {
                    while (in.read(buffer) >= 0) {
                        // the digest is checked as the entry is read
                    }
                }
                if (isSignatureFile(entry.getName())) {
                    continue;
                }
                CodeSigner[] signers = entry.getCodeSigners();
                if (signers == null || signers.length == 0) {
                    unsigned.add(entry.getName());
                    continue;
                }
                signed++;
                String why = null;
                for (CodeSigner signer : signers) {
                    why = verdicts.computeIfAbsent(signer, s -> distrust(s, now));
                    if (why.isEmpty()) {
                        break;
                    }
                }
                if (!why.isEmpty()) {
                    distrusted.add(why);
                }
            }
        } catch (SecurityException e) {
            throw new LoadFailure(Reason.UNTRUSTED_CODE, "jar '" + jar + "' fails signature verification (changed"
                    + " after it was signed?): " + e.getMessage() + "; re-sign it from its original contents", e);
        } catch (IOException e) {
            throw new LoadFailure(Reason.CLASS_NOT_LOADABLE, "jar '" + jar + "' cannot be read: " + e, e);
        }
        if (signed == 0) {
            throw new LoadFailure(Reason.UNTRUSTED_CODE, "jar '" + jar + "' is not signed; sign it with jarsigner"
                    + " using a key whose certificate this node trusts");
        }
        if (!unsigned.isEmpty()) {
            throw new LoadFailure(Reason.UNTRUSTED_CODE, "jar '" + jar + "' is only partly signed: no signature on "
                    + listed(unsigned) + " (added after signing?); sign the whole jar again");
        }
        if (!distrusted.isEmpty()) {
            throw new LoadFailure(Reason.UNTRUSTED_CODE, "jar '" + jar + "' is not signed by a key this node trusts: "
                    + String.join("; ", distrusted) + "; sign it with a trusted key, or trust its"
                    + " certificate in ManagementConfig (trustStore, trustedSigners)");
        }
    }

    /** Why {@code signer} is not trusted, or "" if it is. */
    private String distrust(CodeSigner signer, Date now) {
        List<X509Certificate> chain = new ArrayList<>();
        for (var certificate : signer.getSignerCertPath().getCertificates()) {
            if (!(certificate instanceof X509Certificate x509)) {
                return "a signer's certificate is of type " + certificate.getType() + ", not X.509";
            }
            chain.add(x509);
        }
        X509Certificate leaf = chain.getFirst();
        String who = "'" + leaf.getSubjectX500Principal().getName() + "'";
        int anchorAt = -1;
        for (int i = 0; i < chain.size() && anchorAt < 0; i++) {
            if (trusted.contains(chain.get(i))) {
                anchorAt = i;
            }
        }
        // The signer's own certificate and its issuers up to the trusted one (or all it sent).
        List<X509Certificate> path = anchorAt >= 0 ? chain.subList(0, anchorAt + 1) : chain;
        try {
            for (X509Certificate certificate : path) {
                certificate.checkValidity(now);
            }
            if (anchorAt == 0) {
                return "";
            }
            Set<TrustAnchor> anchors = new LinkedHashSet<>();
            for (X509Certificate certificate : anchorAt > 0 ? List.of(chain.get(anchorAt)) : trusted) {
                anchors.add(new TrustAnchor(certificate, null));
            }
            var parameters = new PKIXParameters(anchors);
            parameters.setRevocationEnabled(false); // no CRL or OCSP infrastructure for plugin keys
            parameters.setDate(now);
            var result = (PKIXCertPathValidatorResult) CertPathValidator.getInstance("PKIX").validate(
                    CertificateFactory.getInstance("X.509").generateCertPath(anchorAt > 0 ? path.subList(0, anchorAt)
                            : path), parameters);
            result.getTrustAnchor().getTrustedCert().checkValidity(now);
            return "";
        } catch (CertificateExpiredException | CertificateNotYetValidException e) {
            return "the certificate chain of signer " + who + " is not valid now (" + e.getMessage() + ")";
        } catch (GeneralSecurityException e) {
            return "signer " + who + " (issued by '" + leaf.getIssuerX500Principal().getName() + "') does not lead to"
                    + " a trusted certificate: " + e.getMessage();
        }
    }

    /** The manifest and the signature files, which jarsigner does not sign (JAR File Specification). */
    private static boolean isSignatureFile(String name) {
        String upper = name.toUpperCase(Locale.ROOT);
        if (upper.equals(JarFile.MANIFEST_NAME)) {
            return true;
        }
        if (!upper.startsWith("META-INF/") || upper.indexOf('/', "META-INF/".length()) >= 0) {
            return false;
        }
        String file = upper.substring("META-INF/".length());
        return file.startsWith("SIG-") || file.endsWith(".SF") || file.endsWith(".DSA") || file.endsWith(".RSA")
                || file.endsWith(".EC");
    }

    private static String listed(List<String> names) {
        String first = String.join("', '", names.subList(0, Math.min(LISTED, names.size())));
        return (names.size() == 1 ? "entry '" : "entries '") + first + "'"
                + (names.size() > LISTED ? " and " + (names.size() - LISTED) + " more" : "");
    }

    static void deleteQuietly(Path file) {
        try {
            Files.deleteIfExists(file);
        } catch (IOException e) {
            // a temporary file; deleteOnExit takes it at the latest
        }
    }
}
