open /etc/passwd
